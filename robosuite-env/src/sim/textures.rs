//! Moving a model's values onto a compilation of the same scene with its texture images:
//! an environment that never renders simulates a scene compiled without them (see
//! [`crate::models::scene::Scene::without_texture_images`]); when it renders or changes
//! textures after all, a model that has the images and every other value of the
//! environment's model is made by copying every array except the texture tables.

use mujoco_rs::mujoco_c::mjModel;
use std::mem::offset_of;

/// The `mjModel` pointer fields left out of [`copy_all_but_textures`]: the texture tables
/// and the asset paths (the scene without images names no image files).
const LEFT_OUT: [usize; 10] = [
    offset_of!(mjModel, tex_type),
    offset_of!(mjModel, tex_colorspace),
    offset_of!(mjModel, tex_height),
    offset_of!(mjModel, tex_width),
    offset_of!(mjModel, tex_nchannel),
    offset_of!(mjModel, tex_adr),
    offset_of!(mjModel, tex_data),
    offset_of!(mjModel, tex_pathadr),
    offset_of!(mjModel, tex_contenttypeadr),
    offset_of!(mjModel, paths),
];

/// The start of every array of `m` in `mjxmacro.h` order, followed by the buffer's end;
/// `None` unless they lie, in order, inside the buffer.
fn array_bounds(m: &mjModel) -> Option<Vec<(usize, usize)>> {
    const WORD: usize = std::mem::size_of::<usize>();
    let first = offset_of!(mjModel, buffer) + WORD;
    let end = offset_of!(mjModel, signature);
    let header = std::ptr::from_ref(m).cast::<u8>();
    let buffer = m.buffer as usize;
    let buffer_end = buffer.checked_add(usize::try_from(m.nbuffer).ok()?)?;
    let mut starts = Vec::with_capacity((end - first) / WORD);
    for offset in (first..end).step_by(WORD) {
        // SAFETY: `offset` is the offset of a pointer field of `mjModel` (every field from
        // `buffer` to `signature` is one), read unaligned to be safe.
        let ptr = unsafe { header.add(offset).cast::<usize>().read_unaligned() };
        starts.push((offset, ptr));
    }
    let mut bounds = Vec::with_capacity(starts.len());
    for (i, &(offset, start)) in starts.iter().enumerate() {
        let next = starts.get(i + 1).map_or(buffer_end, |&(_, p)| p);
        if start < buffer || next < start || next > buffer_end {
            return None;
        }
        bounds.push((offset, next - start));
    }
    Some(bounds)
}

/// Copies every array of `from` into `to`, and its options, visual settings and statistics,
/// except the texture tables and the asset paths: `to` then holds `from`'s values with
/// its own textures. Both must be compilations of one scene that may differ only in their
/// textures' images (and so in `tex_data` and `paths` lengths).
///
/// # Errors
/// A message, with `to` unchanged, when the two models' arrays differ in length anywhere
/// else, or their layout is not MuJoCo's.
pub(crate) fn copy_all_but_textures(from: &mjModel, to: &mut mjModel) -> Result<(), String> {
    let (Some(src), Some(dst)) = (array_bounds(from), array_bounds(to)) else {
        return Err("a model's arrays are not laid out in its buffer as MuJoCo lays them".into());
    };
    if src.len() != dst.len() {
        return Err("the models have different layouts".into());
    }
    for (&(offset, a), &(_, b)) in src.iter().zip(&dst) {
        if a != b && !LEFT_OUT.contains(&offset) {
            return Err(format!(
                "the models differ in more than their textures (the array at header offset \
                 {offset} holds {a} bytes in one and {b} in the other)"
            ));
        }
    }
    let (from_header, to_header) = (
        std::ptr::from_ref(from).cast::<u8>(),
        std::ptr::from_mut(to).cast::<u8>(),
    );
    for &(offset, len) in &src {
        if LEFT_OUT.contains(&offset) || len == 0 {
            continue;
        }
        // SAFETY: both words are pointer fields of their models (see `array_bounds`); the
        // arrays they address lie inside each model's buffer with `len` bytes in both
        // (checked above), and two models' buffers never overlap.
        unsafe {
            let s = from_header.add(offset).cast::<*const u8>().read_unaligned();
            let d = to_header.add(offset).cast::<*mut u8>().read_unaligned();
            std::ptr::copy_nonoverlapping(s, d, len);
        }
    }
    to.opt = from.opt.clone();
    to.vis = from.vis.clone();
    to.stat = from.stat.clone();
    Ok(())
}
