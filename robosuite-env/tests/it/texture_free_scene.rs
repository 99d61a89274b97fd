//! A scene without texture images (for environments that never render) is the same model
//! for physics: equal names and counts, equal physical arrays, much less texture data.

use robosuite_env::assets::Assets;
use robosuite_env::env::compose_scene;
use robosuite_env::models::scene::DEFAULT_MEMORY;
use robosuite_env::{EnvConfig, make_task};

#[test]
fn texture_free_scenes_keep_the_physics_and_drop_the_images() {
    let assets = Assets::locate().unwrap();
    for name in ["Lift", "PickPlaceCan", "Wipe"] {
        let spec = make_task(name).unwrap();
        let scene = compose_scene(spec.as_ref(), &EnvConfig::default(), &assets).unwrap();
        let full = scene.compile(DEFAULT_MEMORY).unwrap();
        let bare = scene
            .without_texture_images()
            .compile(DEFAULT_MEMORY)
            .unwrap();
        let (f, b) = (full.ffi(), bare.ffi());
        for (what, x, y) in [
            ("nbody", f.nbody, b.nbody),
            ("ngeom", f.ngeom, b.ngeom),
            ("nmesh", f.nmesh, b.nmesh),
            ("ntex", f.ntex, b.ntex),
            ("nmat", f.nmat, b.nmat),
            ("nq", f.nq, b.nq),
            ("nv", f.nv, b.nv),
            ("nu", f.nu, b.nu),
        ] {
            assert_eq!(x, y, "{name}: {what}");
        }
        assert!(f.ntex > 0, "{name} has textures");
        assert!(
            b.ntexdata * 100 < f.ntexdata,
            "{name}: texture data {} -> {}",
            f.ntexdata,
            b.ntexdata
        );
        assert_eq!(full.body_mass(), bare.body_mass(), "{name}");
        assert_eq!(full.body_inertia(), bare.body_inertia(), "{name}");
        assert_eq!(full.geom_size(), bare.geom_size(), "{name}");
        assert_eq!(full.geom_friction(), bare.geom_friction(), "{name}");
        assert_eq!(full.body_pos(), bare.body_pos(), "{name}");
        assert_eq!(full.qpos0(), bare.qpos0(), "{name}");
    }
}
