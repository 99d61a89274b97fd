//! [`SharedModel`]: one compiled model whose memory every environment built from the same
//! scene shares, each through its own copy-on-write view.
//!
//! A compiled robosuite scene is tens of MiB (Lift: 62 MiB, mostly mesh data, bounding-volume
//! hierarchies and texture images), nearly all of it never written after compilation. On
//! Linux the model's buffer (every array of `mjModel`) is put once into an anonymous
//! in-memory file (`memfd_create`); each environment maps that file privately
//! (`mmap(MAP_PRIVATE)`) and gets its own `mjModel` header pointing into its mapping. Reads
//! share the file's pages; the first write to a page gives that environment its own copy of
//! the page (the kernel's copy-on-write), so an environment that edits its model (Lift's
//! cube resize, Wipe's markers, Python's `env.sim.model`) changes only its own values and
//! pays only for the pages it wrote. Semantically every view is a private model.
//!
//! Elsewhere (or when the kernel refuses the file) each view is a plain private copy
//! (`mj_copyModel`), as without sharing.

use mujoco_rs::mujoco_c::mjModel;
use mujoco_rs::wrappers::mj_model::MjModel;
use std::mem::ManuallyDrop;
use std::sync::{Arc, OnceLock};

/// A compiled model shared, read-only, by the environments built from it, each through its
/// own copy-on-write view ([`Sim::new_shared`](super::Sim::new_shared)).
///
/// On Linux the model's buffer (every array of `mjModel`) lives in an in-memory file; each
/// view is a private mapping of it (`mmap(MAP_PRIVATE)`) with its own `mjModel` header.
/// Reads share the file's pages; the first write to a page copies that page for the view
/// alone, so every view behaves as a private model while costing only the pages it wrote.
/// Elsewhere (or when the kernel refuses the file) each view is a full copy. Freed when the
/// last handle and the last view are dropped.
pub struct SharedModel {
    inner: Inner,
}

enum Inner {
    /// The buffer in a memory file; `base` reads it through a read-only shared mapping.
    #[cfg(target_os = "linux")]
    Mapped {
        file: std::os::fd::OwnedFd,
        base: ManuallyDrop<MjModel>,
        /// Unmapped after `base`'s header is freed.
        _base_map: Mapping,
    },
    /// A plain model; views are private copies.
    Plain(MjModel),
}

impl std::fmt::Debug for SharedModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SharedModel")
            .field("nbuffer", &self.model().ffi().nbuffer)
            .field("mapped", &self.is_mapped())
            .finish()
    }
}

/// A memory mapping, unmapped on drop.
pub(crate) struct Mapping {
    ptr: *mut u8,
    len: usize,
}

// SAFETY: a mapping is plain memory; who reads or writes it is governed by its owner (a
// read-only base, or one env's view behind `&mut`).
unsafe impl Send for Mapping {}
// SAFETY: as above.
unsafe impl Sync for Mapping {}

impl Drop for Mapping {
    fn drop(&mut self) {
        #[cfg(target_os = "linux")]
        // SAFETY: mapped by `mmap` with this address and length, unmapped once; nothing
        // refers to it any more (its header was freed or retargeted first).
        unsafe {
            libc::munmap(self.ptr.cast(), self.len);
        }
    }
}

/// One environment's view of a [`SharedModel`]: its own `mjModel` header over its own
/// copy-on-write mapping (`None` for a plain copy), keeping the shared model alive.
pub(crate) struct View {
    pub(crate) model: MjModel,
    pub(crate) mapping: Option<(Mapping, Arc<SharedModel>)>,
}

impl View {
    /// Frees the view's header without touching the memory it points into; the mapping is
    /// unmapped afterwards (when dropped).
    ///
    /// # Safety
    /// `model` must be a header made by [`header_over`] (its buffer not MuJoCo's).
    pub(crate) unsafe fn free_header(mut model: MjModel) {
        // SAFETY: the buffer is a mapping, not MuJoCo's allocation: forget it, then
        // `mj_deleteModel` frees only the header (`mju_free(NULL)` does nothing).
        unsafe { model.ffi_mut().buffer = std::ptr::null_mut() };
        drop(model);
    }
}

impl SharedModel {
    /// Puts `model`'s memory where views can share it (on Linux, a memory file; the model
    /// itself is freed), or keeps it as it is when that is not possible.
    ///
    /// Must be called where no other thread runs MuJoCo's XML loader (the first call
    /// compiles a tiny template model).
    pub fn new(model: MjModel) -> Arc<Self> {
        #[cfg(target_os = "linux")]
        if let Ok(inner) = mapped(&model) {
            drop(model);
            return Arc::new(Self { inner });
        }
        Arc::new(Self {
            inner: Inner::Plain(model),
        })
    }

    /// The shared model (read only).
    pub fn model(&self) -> &MjModel {
        match &self.inner {
            #[cfg(target_os = "linux")]
            Inner::Mapped { base, .. } => base,
            Inner::Plain(m) => m,
        }
    }

    /// Whether views share this model's memory page by page (else each is a full copy).
    pub fn is_mapped(&self) -> bool {
        !matches!(self.inner, Inner::Plain(_))
    }

    /// A view for one environment: a private copy-on-write mapping with its own header.
    pub(crate) fn view(self: &Arc<Self>) -> View {
        #[cfg(target_os = "linux")]
        if let Inner::Mapped { file, base, .. } = &self.inner {
            use std::os::fd::AsRawFd;
            let len = base.ffi().nbuffer as usize;
            if let Ok(map) = map_file(
                file.as_raw_fd(),
                len,
                libc::PROT_READ | libc::PROT_WRITE,
                libc::MAP_PRIVATE,
            ) {
                // SAFETY: `map` holds the same bytes as the base's buffer.
                if let Ok(model) = unsafe { header_over(base.ffi(), map.ptr) } {
                    return View {
                        model,
                        mapping: Some((map, Arc::clone(self))),
                    };
                }
            }
        }
        View {
            model: MjModel::clone(self.model()),
            mapping: None,
        }
    }
}

impl Drop for SharedModel {
    fn drop(&mut self) {
        #[cfg(target_os = "linux")]
        if let Inner::Mapped { base, .. } = &mut self.inner {
            // SAFETY: made by `header_over`, dropped once; `base_map` is unmapped after.
            unsafe { View::free_header(ManuallyDrop::take(base)) };
        }
    }
}

/// Byte offsets, in `mjModel`, of the pointer fields into the model's buffer (`buffer`
/// itself included): the words that differ between two copies of one model by exactly the
/// distance between their buffers (MuJoCo assigns every array pointer, empty ones included,
/// inside the buffer). Computed once from a tiny model.
#[cfg(target_os = "linux")]
fn pointer_offsets() -> Option<&'static [usize]> {
    static OFFSETS: OnceLock<Option<Vec<usize>>> = OnceLock::new();
    let offsets = OFFSETS.get_or_init(|| {
        let t = template()?;
        let (a, b) = (MjModel::clone(t), MjModel::clone(t));
        let words = std::mem::size_of::<mjModel>() / 8;
        let wa = std::ptr::from_ref(a.ffi()).cast::<u64>();
        let wb = std::ptr::from_ref(b.ffi()).cast::<u64>();
        let (ba, bb) = (a.ffi().buffer as u64, b.ffi().buffer as u64);
        let found = (0..words)
            .filter(|&k| {
                // SAFETY: `k` < the number of whole 8-byte words of the struct; unaligned
                // reads, as padding may be anywhere.
                let (x, y) = unsafe { (wa.add(k).read_unaligned(), wb.add(k).read_unaligned()) };
                x != y && x.wrapping_sub(ba) == y.wrapping_sub(bb)
            })
            .map(|k| k * 8)
            .collect();
        Some(found)
    });
    offsets.as_deref()
}

/// A tiny compiled model whose copies provide `mjModel` headers (MuJoCo allocates and frees
/// them, as `MjModel` requires).
#[cfg(target_os = "linux")]
fn template() -> Option<&'static MjModel> {
    static TEMPLATE: OnceLock<Option<MjModel>> = OnceLock::new();
    TEMPLATE
        .get_or_init(|| MjModel::from_xml_string("<mujoco><worldbody/></mujoco>").ok())
        .as_ref()
}

/// A model header equal to `src` whose pointers point at the same offsets in `buffer`
/// (which must hold `src.nbuffer` bytes laid out as `src`'s buffer and outlive the header).
///
/// # Errors
/// A message when a pointer field of `src` lies outside its buffer (the header is then freed).
///
/// # Safety
/// `buffer` must hold a copy of `src`'s buffer and live as long as the header; the header
/// must be freed with [`View::free_header`].
#[cfg(target_os = "linux")]
unsafe fn header_over(src: &mjModel, buffer: *mut u8) -> Result<MjModel, String> {
    let (Some(offsets), Some(template)) = (pointer_offsets(), template()) else {
        return Err("MuJoCo did not compile the template model".into());
    };
    let mut header = MjModel::clone(template);
    let from = src.buffer as u64;
    let end = from + src.nbuffer as u64;
    let to = buffer as u64;
    // SAFETY: the template copy's buffer is MuJoCo's and freed once; the struct is then
    // overwritten whole with `src`'s and its pointer words retargeted; on error the header
    // is freed without its (foreign) buffer.
    unsafe {
        mujoco_rs::mujoco_c::mju_free(header.ffi().buffer);
        let dst = header.ffi_mut();
        std::ptr::copy_nonoverlapping(std::ptr::from_ref(src), std::ptr::from_mut(dst), 1);
        let words = std::ptr::from_mut(dst).cast::<u8>();
        for &off in offsets {
            let w = words.add(off).cast::<u64>();
            let v = w.read_unaligned();
            if !(from..=end).contains(&v) {
                View::free_header(header);
                return Err(format!(
                    "a model pointer (offset {off}) lies outside its buffer"
                ));
            }
            w.write_unaligned(v - from + to);
        }
    }
    Ok(header)
}

/// Maps `len` bytes of the file `fd`.
#[cfg(target_os = "linux")]
fn map_file(fd: i32, len: usize, prot: i32, flags: i32) -> Result<Mapping, String> {
    // SAFETY: a fresh mapping of a file of at least `len` bytes; failure is checked.
    let ptr = unsafe { libc::mmap(std::ptr::null_mut(), len, prot, flags, fd, 0) };
    if ptr == libc::MAP_FAILED {
        return Err(format!("mmap: {}", std::io::Error::last_os_error()));
    }
    Ok(Mapping {
        ptr: ptr.cast(),
        len,
    })
}

/// `model`'s buffer in a new memory file, with a read-only header over a shared mapping.
#[cfg(target_os = "linux")]
fn mapped(model: &MjModel) -> Result<Inner, String> {
    use std::io::Write;
    use std::os::fd::{AsRawFd, FromRawFd, OwnedFd};
    let m = model.ffi();
    let len = usize::try_from(m.nbuffer).map_err(|e| e.to_string())?;
    if len == 0 || m.buffer.is_null() {
        return Err("an empty model".into());
    }
    // SAFETY: a NUL-terminated name; the descriptor returned is owned here.
    let fd = unsafe { libc::memfd_create(c"robosuite-rs-model".as_ptr(), libc::MFD_CLOEXEC) };
    if fd < 0 {
        return Err(format!("memfd_create: {}", std::io::Error::last_os_error()));
    }
    // SAFETY: a fresh descriptor owned by nobody else.
    let file = unsafe { OwnedFd::from_raw_fd(fd) };
    let mut writer = std::fs::File::from(file.try_clone().map_err(|e| e.to_string())?);
    // SAFETY: the model's buffer holds `nbuffer` bytes and is not written meanwhile.
    let bytes = unsafe { std::slice::from_raw_parts(m.buffer.cast::<u8>(), len) };
    writer.write_all(bytes).map_err(|e| e.to_string())?;
    drop(writer);
    let base_map = map_file(file.as_raw_fd(), len, libc::PROT_READ, libc::MAP_SHARED)?;
    // SAFETY: `base_map` holds a copy of the buffer and lives in the same `Inner`, dropped
    // after the header (see `Drop for SharedModel`).
    let base = unsafe { header_over(m, base_map.ptr)? };
    Ok(Inner::Mapped {
        file,
        base: ManuallyDrop::new(base),
        _base_map: base_map,
    })
}
