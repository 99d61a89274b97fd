//! robosuite tasks on MuJoCo.

/// Steps a tiny model; temporary link check.
pub fn link_check() -> f64 {
    let model = mujoco_rs::wrappers::mj_model::MjModel::from_xml_string(
        "<mujoco><worldbody><body pos='0 0 1'><freejoint/><geom size='0.1'/></body></worldbody></mujoco>",
    )
    .unwrap();
    let mut data = model.make_data();
    for _ in 0..100 {
        data.step();
    }
    data.qpos()[2]
}

#[cfg(test)]
mod tests {
    #[test]
    fn steps() {
        assert!(super::link_check() < 1.0);
    }
}
