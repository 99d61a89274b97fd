//! Prints what a task's scene holds, as JSON: the counts robosuite reports (`nq`, `nv`,
//! `nu`, `nbody`, ...) and the names of every body, joint, geom, site, actuator, sensor,
//! camera and mesh in model order — the figures to set beside robosuite's own scene.
//! With `--xml`, prints the composed MJCF instead (robosuite's `get_xml()`).
//!
//! `cargo run -p robosuite-env --example scene_info -- Lift [--robot Sawyer] [--xml]`

use mujoco_rs::wrappers::mj_model::MjtObjBase as Obj;

fn main() -> Result<(), gym_core::Error> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let xml = args.iter().any(|a| a == "--xml");
    args.retain(|a| a != "--xml");
    let mut config = robosuite_env::EnvConfig::default();
    if let Some(at) = args.iter().position(|a| a == "--robot") {
        let robot = args.get(at + 1).cloned().unwrap_or_default();
        config = config.with_robots([robot]);
        args.drain(at..(at + 2).min(args.len()));
    }
    let name = args.first().map_or("Lift", String::as_str);
    if xml {
        println!("{}", robosuite_env::scene_xml(name, &config)?);
        return Ok(());
    }
    let env = robosuite_env::make_with(name, config)?;
    let m = env.sim().model();
    let f = m.ffi();
    let kinds = [
        ("body", Obj::mjOBJ_BODY, f.nbody),
        ("joint", Obj::mjOBJ_JOINT, f.njnt),
        ("geom", Obj::mjOBJ_GEOM, f.ngeom),
        ("site", Obj::mjOBJ_SITE, f.nsite),
        ("actuator", Obj::mjOBJ_ACTUATOR, f.nu),
        ("sensor", Obj::mjOBJ_SENSOR, f.nsensor),
        ("camera", Obj::mjOBJ_CAMERA, f.ncam),
        ("mesh", Obj::mjOBJ_MESH, f.nmesh),
    ];
    println!("{{");
    println!(
        "  \"counts\": {{\"nq\": {}, \"nv\": {}, \"nu\": {}, \"nbody\": {}, \"njnt\": {}, \"ngeom\": {}, \"nsite\": {}, \"nmesh\": {}, \"nsensor\": {}, \"ncam\": {}}},",
        f.nq, f.nv, f.nu, f.nbody, f.njnt, f.ngeom, f.nsite, f.nmesh, f.nsensor, f.ncam
    );
    println!("  \"names\": {{");
    for (k, (label, kind, n)) in kinds.iter().enumerate() {
        let names: Vec<String> = (0..*n as usize)
            .map(|i| format!("\"{}\"", m.id_to_name(*kind, i).unwrap_or("")))
            .collect();
        let comma = if k + 1 < kinds.len() { "," } else { "" };
        println!("    \"{label}\": [{}]{comma}", names.join(", "));
    }
    println!("  }}");
    println!("}}");
    Ok(())
}
