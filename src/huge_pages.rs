//! Transparent huge pages (2 MiB) for the large arrays rays read at random:
//! a mesh's wide BVH nodes and its packed triangles.
//!
//! A large mesh's BVH and triangles (48 bytes a triangle: 48 MB for a
//! million) are read at random by incoherent rays, and 4 KiB pages spread
//! them over ~12,000 TLB entries' worth of memory, 2 MiB pages over 24.
//! Linux backs memory with huge pages only where asked
//! (`madvise(MADV_HUGEPAGE)`) on most distributions
//! (`/sys/kernel/mm/transparent_hugepage/enabled` set to `madvise`), and
//! Embree asks for its BVH; ronray did not. The advice is given on a freshly
//! allocated array before it is written, so its pages are huge from their
//! first fault. Measured on the 1M-triangle mesh (`ronray bench`, ten runs
//! alternated with a build without it, one thread): incoherent closest hits
//! 1.52 ± 0.14 against 1.43 ± 0.11 Mrays/s; on two threads and in build time
//! nothing showed through the machine's noise.
//!
//! Only those arrays are advised, not the build's scratch arrays: advising
//! every allocation of 4 MiB or more (a global allocator) gave about the
//! same traversal gain and a ~15% slower build (each huge page is zeroed,
//! and maybe compacted for, at its first write).
//!
//! Only the whole 2 MiB-aligned pages inside an allocation are advised, and
//! a huge page is backed whole at its first write, so an array holds at
//! most one huge page more than the memory it has written. Where the kernel
//! refuses (huge pages off, not Linux) the advice is dropped and nothing
//! else changes.

/// Arrays smaller than this are left alone: a huge page is only worth it
/// where the data spans several.
const THRESHOLD: usize = 4 << 20;
/// The x86-64 and AArch64 (4 KiB granule) transparent huge page.
const HUGE_PAGE: usize = 2 << 20;

/// Asks the kernel to back `v`'s buffer (its whole capacity) with huge
/// pages, if it is at least 4 MiB. Call it on a new vector before writing
/// it: pages already written keep their small pages until the kernel's
/// background collapsing gets to them.
pub fn advise<T>(v: &Vec<T>) {
    advise_range(v.as_ptr().cast(), v.capacity().saturating_mul(size_of::<T>()));
}

/// Asks for huge pages over the whole 2 MiB-aligned pages of `p..p + len`
/// when `len` is at least [`THRESHOLD`].
fn advise_range(p: *const u8, len: usize) {
    if len < THRESHOLD || p.is_null() {
        return;
    }
    let (start, end) = huge_range(p as usize, len);
    #[cfg(target_os = "linux")]
    if end > start {
        // SAFETY: `start..end` lies inside the live allocation at `p`;
        // MADV_HUGEPAGE changes no contents. An error (THP compiled out or
        // disabled) leaves the pages as they were, which is fine.
        unsafe {
            libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (start, end);
}

/// The whole huge pages inside `addr..addr + len`, as an address range
/// (empty when there is none).
fn huge_range(addr: usize, len: usize) -> (usize, usize) {
    let start = addr.next_multiple_of(HUGE_PAGE);
    let end = (addr + len) / HUGE_PAGE * HUGE_PAGE;
    (start, end.max(start))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_whole_huge_pages_inside_the_allocation_are_advised() {
        let mb = 1 << 20;
        // Aligned: all of it.
        assert_eq!(huge_range(4 * mb, 6 * mb), (4 * mb, 10 * mb));
        // Unaligned both ends: the pages strictly inside.
        assert_eq!(huge_range(4 * mb + 4096, 6 * mb), (6 * mb, 10 * mb));
        // No whole page inside: empty.
        let (s, e) = huge_range(mb, 2 * mb);
        assert_eq!(s, e);
    }

    #[test]
    fn advised_arrays_keep_working() {
        // Advice on a fresh array, then writes and growth: contents intact
        // (the advice changes how pages are backed, never what they hold).
        let mut v: Vec<u32> = Vec::with_capacity(3 << 20);
        advise(&v);
        v.extend(0..3 << 20);
        advise(&v);
        v.extend(0..1 << 20);
        assert!(v[..3 << 20].iter().enumerate().all(|(i, &x)| x == i as u32));
        assert_eq!(v[(3 << 20) + 5], 5);
        // Small and empty arrays are left alone.
        advise(&Vec::<u8>::new());
        advise(&vec![1u8; 100]);
    }
}
