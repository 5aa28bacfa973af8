"""A sampling profiler for machines without `perf` (this one reports no
hardware counters): where a running ronray spends *time*, to set beside
callgrind's instruction counts. A function whose share of time is well
above its share of instructions is stalling (branch mispredicts, long
latency chains, denormal assists, failed store forwarding); issue 18's
denormal assists were found by such a gap.

Every INTERVAL seconds it ptrace-attaches the process's busiest thread,
reads its program counter and detaches (the thread stops for ~0.1 ms), then
maps the counters to functions and source lines with `addr2line` (binutils)
and prints the top of each. Linux x86-64 only; attaching needs the same
user and a `ptrace_scope` that allows it (0, or root). Not part of ronray: a
measuring tool.

Usage: python3 tools/pc_sample.py PID [SECONDS] [INTERVAL]
  e.g. target/release/ronray render scenes/cornell.ron --threads 1 \\
           --size 512x512 --spp 256 --progress none -o /tmp/x.exr &
       python3 tools/pc_sample.py $! 20
SECONDS defaults to 10, INTERVAL to 0.002."""
import collections, ctypes, os, subprocess, sys, time

PTRACE_GETREGS, PTRACE_ATTACH, PTRACE_DETACH = 12, 16, 17
RIP = 16  # index of rip in x86-64's struct user_regs_struct
WALL = 0x40000000  # __WALL: wait for any thread


def busiest_thread(pid):
    best = None
    for t in os.listdir(f'/proc/{pid}/task'):
        fields = open(f'/proc/{pid}/task/{t}/stat').read().rsplit(')', 1)[1].split()
        ticks = int(fields[11]) + int(fields[12])
        if best is None or ticks > best[0]:
            best = (ticks, int(t))
    return best[1]


def load_base(pid, exe):
    base = None
    for line in open(f'/proc/{pid}/maps'):
        parts = line.split()
        if len(parts) >= 6 and parts[5] == exe:
            lo, off = int(parts[0].split('-')[0], 16), int(parts[2], 16)
            base = lo - off if base is None else min(base, lo - off)
    return base


def sample(pid, seconds, interval):
    libc = ctypes.CDLL(None, use_errno=True)
    libc.ptrace.restype = ctypes.c_long
    libc.ptrace.argtypes = [ctypes.c_long, ctypes.c_long, ctypes.c_void_p, ctypes.c_void_p]
    exe = os.readlink(f'/proc/{pid}/exe')
    base = load_base(pid, exe)
    time.sleep(0.5)  # let the render's threads start
    tid = busiest_thread(pid)
    regs = (ctypes.c_ulonglong * 27)()
    pcs = []
    end = time.time() + seconds
    while time.time() < end:
        if libc.ptrace(PTRACE_ATTACH, tid, None, None) != 0:
            break  # the thread is gone (or attaching is not allowed)
        os.waitpid(tid, WALL)
        libc.ptrace(PTRACE_GETREGS, tid, None, ctypes.byref(regs))
        pcs.append(regs[RIP] - base)
        libc.ptrace(PTRACE_DETACH, tid, None, None)
        # A slightly varying period, so the samples cannot lock onto a loop.
        time.sleep(interval * (1 + (len(pcs) % 7) / 7))
    return exe, pcs


def report(exe, pcs):
    counts = collections.Counter(pcs)
    addrs = sorted(counts)
    # -a marks each address's block; -i lists the inlining chain, innermost
    # first: the line is the innermost's, the function the outermost's.
    out = subprocess.run(['addr2line', '-a', '-i', '-f', '-C', '-e', exe] + ['%x' % a for a in addrs],
                         capture_output=True, text=True).stdout.splitlines()
    blocks, cur = [], None
    for row in out:
        if row.startswith('0x'):
            cur = []
            blocks.append(cur)
        elif cur is not None:
            cur.append(row)
    func, line = collections.Counter(), collections.Counter()
    for a, b in zip(addrs, blocks):
        pairs = list(zip(b[0::2], b[1::2])) or [('??', '??:0')]
        func[pairs[-1][0][:100]] += counts[a]
        line[f'{pairs[0][1].split("/")[-1]}  ({pairs[-1][0][:60]})'] += counts[a]
    total = len(pcs)
    print(f'{total} samples')
    for title, c in (('functions', func), ('source lines', line)):
        print(f'\n== {title}')
        for k, v in c.most_common(20):
            print(f'{100 * v / total:6.1f}%  {k}')


if __name__ == '__main__':
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    pid = int(sys.argv[1])
    seconds = float(sys.argv[2]) if len(sys.argv) > 2 else 10.0
    interval = float(sys.argv[3]) if len(sys.argv) > 3 else 0.002
    exe, pcs = sample(pid, seconds, interval)
    if not pcs:
        sys.exit('no samples: could not attach (same user? /proc/sys/kernel/yama/ptrace_scope?)')
    report(exe, pcs)
