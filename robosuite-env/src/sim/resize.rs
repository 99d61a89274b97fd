//! Resizing a box- or cylinder-shaped body in place, the run-time equivalent of recompiling
//! a model whose primitive was drawn with another size (robosuite re-draws Lift's cube and
//! TwoArmPegInHole's peg at every hard reset).

use super::{Data, Sim};
use gym_core::{Error, Result};
use mujoco_rs::wrappers::mj_model::MjModel;

/// The box geoms and their body that [`resize_box_body`] edits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoxGeomUpdate<'a> {
    /// The body that holds the boxes and nothing else with mass.
    pub body: usize,
    /// The box geoms (type box, at the body's origin, aligned with it, all of one size):
    /// the first is the collision geom whose density gives the mass; the others (robosuite's
    /// visual copy) have no mass.
    pub geoms: &'a [usize],
    /// The density the mass follows (kg/m³).
    pub density: f64,
}

/// Gives the box geoms the half-extents `half` and updates everything the compiler derives
/// from them: `geom_size`, `geom_rbound`, `geom_aabb`, the body's bounding-volume boxes,
/// `body_mass` and `body_inertia` (solid box of the given density, as MuJoCo's compiler),
/// `mj_setConst` for the constants derived from masses (subtree masses, inverse weights,
/// ...), and the statistics the compiler computes but `mj_setConst` does not
/// (`stat.meanmass`, `stat.meaninertia`, `stat.meansize`, the body's `dof_length`). Leaves
/// the data at `qpos0`: call `mj_resetData` (or set a state) afterwards.
///
/// # Errors
/// [`Error::InvalidArgument`] for non-positive or non-finite half-extents.
pub fn resize_box_body(sim: &mut Sim, target: BoxGeomUpdate<'_>, half: [f64; 3]) -> Result<()> {
    if half.iter().any(|h| !h.is_finite() || *h <= 0.0) {
        return Err(Error::invalid_argument(
            "half_extents",
            format!("must be positive and finite, got {half:?}"),
        ));
    }
    let [x, y, z] = half;
    let mass = target.density * 8.0 * x * y * z;
    let inertia = [
        mass * (y * y + z * z) / 3.0,
        mass * (x * x + z * z) / 3.0,
        mass * (x * x + y * y) / 3.0,
    ];
    let rbound = (x * x + y * y + z * z).sqrt();
    resize_body(sim, target, half, half, rbound, mass, inertia)
}

/// The arena of the scratch data [`resized_box_bodies`] works in: enough for `mj_setConst`
/// and a mass matrix (scenes may reserve a gigabyte for contacts, which is never touched
/// here but would be allocated and cleared).
const SCRATCH_ARENA: i64 = 16 << 20;

/// A copy of `model` with each box body of `targets` resized as [`resize_box_body`] does
/// (`(update, half-extents)`), computed in a scratch data of small arena; the copy keeps
/// every size of `model` (its arena included).
///
/// # Errors
/// As [`resize_box_body`]; [`Error::Model`] when MuJoCo cannot allocate the scratch data.
pub fn resized_box_bodies(
    model: &MjModel,
    targets: &[(BoxGeomUpdate<'_>, [f64; 3])],
) -> Result<MjModel> {
    let mut copy = MjModel::clone(model);
    let narena = model.ffi().narena;
    // SAFETY: only the arena size of this private copy changes, before any data is made for
    // it; it is put back on the copy returned.
    unsafe { copy.ffi_mut().narena = narena.min(SCRATCH_ARENA) };
    let data = Data::new(copy).map_err(|e| Error::model(format!("cannot allocate mjData: {e}")))?;
    let mut sim = Sim { data, failed: None };
    for (target, half) in targets {
        resize_box_body(&mut sim, *target, *half)?;
    }
    let Some(mut out) = sim.data.into_model() else {
        return Err(Error::model("the scratch data does not own its model"));
    };
    // SAFETY: as above: the arena size of the model's own copy, no data made for it yet.
    unsafe { out.ffi_mut().narena = narena };
    Ok(out)
}

/// As [`resize_box_body`] for cylinder geoms (at the body's origin, along its z axis):
/// radius `radius` and half-height `half_height`; mass and inertia of a solid cylinder.
///
/// # Errors
/// [`Error::InvalidArgument`] for a non-positive or non-finite size.
pub fn resize_cylinder_body(
    sim: &mut Sim,
    target: BoxGeomUpdate<'_>,
    radius: f64,
    half_height: f64,
) -> Result<()> {
    if ![radius, half_height]
        .iter()
        .all(|v| v.is_finite() && *v > 0.0)
    {
        return Err(Error::invalid_argument(
            "size",
            format!(
                "a cylinder needs a positive radius and half-height, got {radius}, {half_height}"
            ),
        ));
    }
    let (r, h) = (radius, half_height);
    let mass = target.density * std::f64::consts::PI * r * r * 2.0 * h;
    let side = mass * (3.0 * r * r + 4.0 * h * h) / 12.0;
    let inertia = [side, side, mass * r * r / 2.0];
    let rbound = (r * r + h * h).sqrt();
    resize_body(sim, target, [r, h, 0.0], [r, r, h], rbound, mass, inertia)
}

/// Writes a primitive body's new geom `size` (with the half-extents `half` of its bounding
/// box and its bounding radius `rbound`), mass and inertia, then derives the rest as [`resize_box_body`] describes.
fn resize_body(
    sim: &mut Sim,
    target: BoxGeomUpdate<'_>,
    size: [f64; 3],
    half: [f64; 3],
    rbound: f64,
    mass: f64,
    inertia: [f64; 3],
) -> Result<()> {
    let Some(&main) = target.geoms.first() else {
        return Err(Error::invalid_argument("geoms", "no geom to resize"));
    };
    let old_rbound = sim.model().geom_rbound()[main];
    {
        let model = sim.model_mut();
        for &g in target.geoms {
            model.geom_size_mut()[g] = size;
            model.geom_rbound_mut()[g] = rbound;
            model.geom_aabb_mut()[g][3..6].copy_from_slice(&half);
        }
        model.body_mass_mut()[target.body] = mass;
        model.body_inertia_mut()[target.body] = inertia;
        let adr = model.body_bvhadr()[target.body];
        let num = model.body_bvhnum()[target.body];
        if adr >= 0 {
            let bvh = model.bvh_aabb_mut();
            for node in adr as usize..(adr + num) as usize {
                if let Some(b) = bvh.get_mut(node) {
                    b[3..6].copy_from_slice(&half);
                }
            }
        }
    }
    let (m, d) = sim.raw_mut();
    // SAFETY: m and d belong together; mj_setConst only rewrites constant fields of the model
    // (no sizes) and uses the data as scratch.
    unsafe { mujoco_rs::mujoco_c::mj_setConst(m, d) };
    update_statistics(sim, target.body, main, old_rbound);
    Ok(())
}

/// Recomputes `stat.meanmass`, `stat.meaninertia`, `stat.meansize` and the body's
/// `dof_length` as the compiler's `setStat` does (for a body whose size is its geom's
/// bounding radius: a single geom at the body origin).
fn update_statistics(sim: &mut Sim, body: usize, main: usize, old_rbound: f64) {
    let (nbody, nv) = {
        let m = sim.model().ffi();
        (m.nbody as usize, m.nv as usize)
    };
    // Diagonal of the mass matrix at qpos0.
    sim.reset_data();
    sim.data_mut().mass_matrix_stages();
    let mut full = vec![0.0; nv * nv];
    let meaninertia = if sim.data().full_m(&mut full).is_ok() && nv > 0 {
        (0..nv).map(|i| full[i * nv + i]).sum::<f64>() / nv as f64
    } else {
        sim.model().stat().meaninertia
    };
    let model = sim.model_mut();
    let new_rbound = model.geom_rbound()[main];
    if nbody > 1 {
        let meanmass = model.body_mass()[1..].iter().sum::<f64>() / (nbody - 1) as f64;
        let meansize = model.stat().meansize
            + (new_rbound.max(1e-5) - old_rbound.max(1e-5)) / (nbody - 1) as f64;
        let stat = model.stat_mut();
        stat.meanmass = meanmass;
        stat.meansize = meansize;
    }
    model.stat_mut().meaninertia = meaninertia;
    let (adr, num) = (model.body_dofadr()[body], model.body_dofnum()[body]);
    if adr >= 0 {
        let jnt = model.body_jntadr()[body];
        let free =
            jnt >= 0 && model.jnt_type()[jnt as usize] == mujoco_rs::mujoco_c::mjtJoint::mjJNT_FREE;
        for (k, dof) in (adr as usize..(adr + num) as usize).enumerate() {
            // Translational dofs of a free joint keep length 1; rotational ones take the body size.
            if !(free && k < 3) {
                model.dof_length_mut()[dof] = new_rbound.max(1e-5);
            }
        }
    }
}

/// Gives `body` the geometry and mass of `donor_body` in `donor`, a small model compiled
/// from the same body with other figures (an object whose several geoms robosuite re-draws
/// at every hard reset, such as the hammer): per geom (in order) size, position,
/// orientation, friction, bounding radius and box; the body's mass, inertia and inertial
/// frame; its bounding-volume hierarchy; its dofs' length scales; then, as
/// [`resize_box_body`], `mj_setConst` and the statistics (`meansize` moved by the change of
/// the body's own size, `donor_size − old_size`, read from single-body donors). Leaves the
/// data at `qpos0`.
///
/// # Errors
/// [`Error::Model`] when the donor body's geoms, bounding volumes or dofs do not
/// correspond to the body's.
pub fn reshape_body_from(
    sim: &mut Sim,
    body: usize,
    donor: &mujoco_rs::wrappers::mj_model::MjModel,
    donor_body: usize,
    size_change: f64,
) -> Result<()> {
    let count = |m: &mujoco_rs::wrappers::mj_model::MjModel, b: usize| {
        (
            m.body_geomadr()[b],
            m.body_geomnum()[b],
            m.body_bvhadr()[b],
            m.body_bvhnum()[b],
            m.body_dofadr()[b],
            m.body_dofnum()[b],
        )
    };
    let (ga, gn, ba, bn, da, dn) = count(sim.model(), body);
    let (dga, dgn, dba, dbn, dda, ddn) = count(donor, donor_body);
    if gn != dgn || bn != dbn || dn != ddn || ga < 0 || dga < 0 {
        return Err(Error::model(format!(
            "the donor body has {dgn} geoms, {dbn} bounding volumes and {ddn} dofs; \
             the body {gn}, {bn} and {dn}"
        )));
    }
    let old_rbound = sim.model().geom_rbound()[ga as usize];
    let geom_offset = ga - dga;
    {
        let model = sim.model_mut();
        for k in 0..gn as usize {
            let (g, dg) = (ga as usize + k, dga as usize + k);
            model.geom_size_mut()[g] = donor.geom_size()[dg];
            model.geom_pos_mut()[g] = donor.geom_pos()[dg];
            model.geom_quat_mut()[g] = donor.geom_quat()[dg];
            model.geom_friction_mut()[g] = donor.geom_friction()[dg];
            model.geom_rbound_mut()[g] = donor.geom_rbound()[dg];
            model.geom_aabb_mut()[g] = donor.geom_aabb()[dg];
            model.geom_sameframe_mut()[g] = donor.geom_sameframe()[dg];
        }
        model.body_mass_mut()[body] = donor.body_mass()[donor_body];
        model.body_inertia_mut()[body] = donor.body_inertia()[donor_body];
        model.body_ipos_mut()[body] = donor.body_ipos()[donor_body];
        model.body_iquat_mut()[body] = donor.body_iquat()[donor_body];
        model.body_sameframe_mut()[body] = donor.body_sameframe()[donor_body];
        if ba >= 0 && dba >= 0 {
            for k in 0..bn as usize {
                let (n, dn_) = (ba as usize + k, dba as usize + k);
                if let (Some(to), Some(from)) =
                    (model.bvh_aabb_mut().get_mut(n), donor.bvh_aabb().get(dn_))
                {
                    *to = *from;
                }
                model.bvh_depth_mut()[n] = donor.bvh_depth()[dn_];
                let id = donor.bvh_nodeid()[dn_];
                let child = donor.bvh_child()[dn_];
                // SAFETY: the donor's hierarchy has the same number of nodes; node ids (global
                // geom ids) are shifted to this body's geoms, and child indices (relative to
                // the body's root node) are kept, so every index stays inside the arrays.
                unsafe {
                    model.bvh_nodeid_mut()[n] = if id >= 0 { id + geom_offset } else { id };
                    model.bvh_child_mut()[n] = child;
                }
            }
        }
        if da >= 0 {
            for k in 0..dn as usize {
                model.dof_length_mut()[da as usize + k] = donor.dof_length()[dda as usize + k];
            }
        }
    }
    let (m, d) = sim.raw_mut();
    // SAFETY: as in resize_box_body.
    unsafe { mujoco_rs::mujoco_c::mj_setConst(m, d) };
    let nbody = sim.model().ffi().nbody as usize;
    update_statistics(sim, body, ga as usize, old_rbound);
    // `update_statistics` moved meansize by the first geom's radius and rewrote the dof
    // lengths from it: restore the donor's dof lengths and apply the body's own size change.
    let model = sim.model_mut();
    if da >= 0 {
        for k in 0..dn as usize {
            model.dof_length_mut()[da as usize + k] = donor.dof_length()[dda as usize + k];
        }
    }
    if nbody > 1 {
        let new_rbound = model.geom_rbound()[ga as usize];
        let geom_shift = (new_rbound.max(1e-5) - old_rbound.max(1e-5)) / (nbody - 1) as f64;
        model.stat_mut().meansize += size_change / (nbody - 1) as f64 - geom_shift;
    }
    Ok(())
}
