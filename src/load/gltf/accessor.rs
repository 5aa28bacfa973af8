//! glTF accessors read into plain arrays, checked before any byte is read:
//! the `gltf` crate's own reader slices buffers unchecked in places (a
//! zero count underflows, a short stride asserts), so a hostile file would
//! panic there. Every accessor here is bounded by the bytes that back it
//! (so no count allocates more than the file holds), except one without a
//! buffer view (all zeros plus sparse values), which [`MAX_ELEMENTS`] caps.
//!
//! Handles byte strides (interleaved views), normalised integers
//! (glTF 2.0 §3.11: `f = max(c / (2ⁿ⁻¹ − 1), −1)` signed, `c / (2ⁿ − 1)`
//! unsigned) and sparse substitution (§3.6.2.3).

use gltf::Document;
use gltf::accessor::{DataType, Dimensions};

/// Elements in one accessor at most: 2²⁴ (a 16M-vertex primitive); an
/// accessor without data would otherwise allocate `count` elements from a
/// number in the file.
pub const MAX_ELEMENTS: usize = 1 << 24;

/// The buffers' bytes, by buffer index.
pub type Buffers = [Vec<u8>];

/// Accessor `index` as `N` floats per element, for a list of allowed
/// shapes (`what` names the attribute in errors).
pub fn read_f32<const N: usize>(
    doc: &Document,
    buffers: &Buffers,
    index: usize,
    dims: Dimensions,
    allowed: &[DataType],
    what: &str,
) -> Result<Vec<[f32; N]>, String> {
    let raw = read_raw(doc, buffers, index, dims, allowed, what)?;
    Ok(raw
        .chunks_exact(N)
        .map(|c| std::array::from_fn(|k| c[k]))
        .collect())
}

/// Accessor `index` as vertex indices (unsigned integers, not normalised).
pub fn read_indices(doc: &Document, buffers: &Buffers, index: usize) -> Result<Vec<u32>, String> {
    let allowed = [DataType::U8, DataType::U16, DataType::U32];
    let a = doc
        .accessors()
        .nth(index)
        .ok_or_else(|| format!("indices: accessor {index} does not exist"))?;
    if a.normalized() {
        return Err(format!(
            "accessors[{index}] (indices): indices cannot be normalised"
        ));
    }
    if a.dimensions() != Dimensions::Scalar || !allowed.contains(&a.data_type()) {
        return Err(format!(
            "accessors[{index}] (indices): {:?} of {:?}, expected scalar unsigned integers",
            a.dimensions(),
            a.data_type()
        ));
    }
    let mut out = Vec::new();
    for_each_element(doc, buffers, index, &mut |bytes, ty| {
        out.push(component_u32(bytes, ty))
    })?;
    Ok(out)
}

/// All components of accessor `index` as floats (normalised integers
/// mapped to [0, 1] or [−1, 1]).
fn read_raw(
    doc: &Document,
    buffers: &Buffers,
    index: usize,
    dims: Dimensions,
    allowed: &[DataType],
    what: &str,
) -> Result<Vec<f32>, String> {
    let a = doc
        .accessors()
        .nth(index)
        .ok_or_else(|| format!("{what}: accessor {index} does not exist"))?;
    let at = format!("accessors[{index}] ({what})");
    if a.dimensions() != dims {
        return Err(format!("{at}: type {:?}, expected {dims:?}", a.dimensions()));
    }
    if !allowed.contains(&a.data_type()) {
        return Err(format!(
            "{at}: component type {:?} is not allowed here",
            a.data_type()
        ));
    }
    let mut out = Vec::new();
    let norm = a.normalized();
    for_each_element(doc, buffers, index, &mut |bytes, ty| {
        out.push(component_f32(bytes, ty, norm));
    })?;
    Ok(out)
}

/// Calls `f` with each component's bytes of accessor `index`, in order,
/// after every range has been checked; sparse values replace their
/// elements.
fn for_each_element(
    doc: &Document,
    buffers: &Buffers,
    index: usize,
    f: &mut dyn FnMut(&[u8], DataType),
) -> Result<(), String> {
    let a = doc
        .accessors()
        .nth(index)
        .ok_or_else(|| format!("accessor {index} does not exist"))?;
    let at = format!("accessors[{index}]");
    let (count, ty) = (a.count(), a.data_type());
    let comps = a.dimensions().multiplicity();
    let size = ty.size();
    let elem = size * comps;
    if count == 0 {
        return Err(format!("{at}: count is 0"));
    }
    if count > MAX_ELEMENTS {
        return Err(format!(
            "{at}: {count} elements, more than the limit of {MAX_ELEMENTS}"
        ));
    }
    // Dense data: the view's bytes, or zeros.
    let mut dense: Vec<&[u8]> = Vec::new();
    let zeros = vec![0u8; elem];
    match a.view() {
        Some(view) => {
            let bytes = view_bytes(buffers, &view, &at)?;
            let stride = view.stride().unwrap_or(elem);
            if stride < elem {
                return Err(format!(
                    "{at}: byte stride {stride} is shorter than an element ({elem} bytes)"
                ));
            }
            let start = a.offset();
            let end = (count - 1)
                .checked_mul(stride)
                .and_then(|x| x.checked_add(start))
                .and_then(|x| x.checked_add(elem))
                .is_some_and(|e| e <= bytes.len());
            if !end {
                return Err(format!(
                    "{at}: {count} elements of {elem} bytes (stride {stride}) from byte {start} run past its buffer view of {} bytes",
                    bytes.len()
                ));
            }
            dense.reserve(count);
            for k in 0..count {
                let s = start + k * stride;
                dense.push(&bytes[s..s + elem]);
            }
        }
        None => {
            if a.sparse().is_none() {
                return Err(format!("{at}: no buffer view and no sparse values"));
            }
            dense = vec![zeros.as_slice(); count];
        }
    }
    if let Some(sparse) = a.sparse() {
        let n = sparse.count();
        if n > count {
            return Err(format!("{at}.sparse: {n} values for {count} elements"));
        }
        let iview = sparse.indices().view();
        let ibytes = view_bytes(buffers, &iview, &format!("{at}.sparse.indices"))?;
        let ity = match sparse.indices().index_type() {
            gltf::accessor::sparse::IndexType::U8 => DataType::U8,
            gltf::accessor::sparse::IndexType::U16 => DataType::U16,
            gltf::accessor::sparse::IndexType::U32 => DataType::U32,
        };
        let istart = sparse.indices().offset();
        let vview = sparse.values().view();
        let vbytes = view_bytes(buffers, &vview, &format!("{at}.sparse.values"))?;
        let vstart = sparse.values().offset();
        let fits = |start: usize, each: usize, len: usize| {
            n.checked_mul(each)
                .and_then(|x| x.checked_add(start))
                .is_some_and(|e| e <= len)
        };
        if !fits(istart, ity.size(), ibytes.len()) || !fits(vstart, elem, vbytes.len()) {
            return Err(format!(
                "{at}.sparse: {n} indices or values run past their buffer views"
            ));
        }
        for k in 0..n {
            let i = component_u32(&ibytes[istart + k * ity.size()..], ity) as usize;
            let Some(slot) = dense.get_mut(i) else {
                return Err(format!(
                    "{at}.sparse.indices[{k}] = {i}, past the {count} elements"
                ));
            };
            *slot = &vbytes[vstart + k * elem..vstart + (k + 1) * elem];
        }
    }
    for e in dense {
        for c in 0..comps {
            f(&e[c * size..], ty);
        }
    }
    Ok(())
}

/// The bytes of a buffer view, checked against its buffer.
fn view_bytes<'b>(buffers: &'b Buffers, view: &gltf::buffer::View, at: &str) -> Result<&'b [u8], String> {
    let b = view.buffer().index();
    let data = buffers
        .get(b)
        .ok_or_else(|| format!("{at}: buffer {b} was not loaded"))?;
    let (start, len) = (view.offset(), view.length());
    start
        .checked_add(len)
        .and_then(|end| data.get(start..end))
        .ok_or_else(|| {
            format!(
                "{at}: bufferViews[{}] spans bytes {start}..{} of buffer {b}, which has {} (truncated?)",
                view.index(),
                start.saturating_add(len),
                data.len()
            )
        })
}

fn component_u32(b: &[u8], ty: DataType) -> u32 {
    match ty {
        DataType::U8 | DataType::I8 => u32::from(b[0]),
        DataType::U16 | DataType::I16 => u32::from(u16::from_le_bytes([b[0], b[1]])),
        DataType::U32 | DataType::F32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
    }
}

fn component_f32(b: &[u8], ty: DataType, normalized: bool) -> f32 {
    let (v, max) = match ty {
        DataType::F32 => return f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        DataType::U8 => (f32::from(b[0]), 255.0),
        DataType::I8 => (f32::from(b[0] as i8), 127.0),
        DataType::U16 => (f32::from(u16::from_le_bytes([b[0], b[1]])), 65535.0),
        DataType::I16 => (f32::from(i16::from_le_bytes([b[0], b[1]])), 32767.0),
        DataType::U32 => (
            u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32,
            u32::MAX as f32,
        ),
    };
    if normalized { (v / max).max(-1.0) } else { v }
}
