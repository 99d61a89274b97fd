//! MuJoCo calls that return a fatal MuJoCo error as a typed error instead of ending the
//! process.
//!
//! MuJoCo reports a fatal error (an arena too small for a step: "mj_stackAlloc: out of
//! memory", an allocation that fails, ...) through its error handler, and its default handler
//! calls `exit()`. A handler must not return either: MuJoCo cannot continue after the error.
//! The usual C pattern is a `setjmp` before the call and a `longjmp` from the handler, but a
//! `longjmp` over Rust frames is undefined behaviour, and unwinding a Rust panic through
//! MuJoCo's C frames is not sound either. So the `setjmp` lives in a small C shim
//! (`csrc/guard.c`, compiled by the build with the `cc` crate): each guarded function
//! installs MuJoCo's *thread-local* log handler (the mechanism MuJoCo's own Python bindings
//! use), calls `sigsetjmp`, then the MuJoCo function; the handler copies the message and
//! `siglongjmp`s back into the shim. Only C frames (the shim and MuJoCo) lie between the two,
//! and this crate installs no MuJoCo callback (`mjcb_*`) through which MuJoCo could call Rust
//! code in between. The previous thread-local handler is restored afterwards, so other code
//! on the thread is unaffected, and other threads never see the handler.
//!
//! After an error, the `mjData` stack is left as MuJoCo left it; [`Sim`](super::Sim) marks
//! itself failed and refuses every further MuJoCo call until `mj_resetData` (which resets the
//! stack and arena) has run. Warnings are dropped by the handler: the env reads MuJoCo's
//! warning counters (`mjData.warning`) instead. The cost is two thread-local handler swaps
//! and a `sigsetjmp` (no signal mask saved) per MuJoCo call: well under 0.1 µs, against
//! tens of microseconds per substep; nothing is allocated unless an error happened.

use mujoco_rs::mujoco_c::{mjData, mjModel};
use std::ffi::{CStr, c_char, c_int, c_void};

unsafe extern "C" {
    fn rs_guard_step(m: *const c_void, d: *mut c_void) -> c_int;
    fn rs_guard_step1(m: *const c_void, d: *mut c_void) -> c_int;
    fn rs_guard_step2(m: *const c_void, d: *mut c_void) -> c_int;
    fn rs_guard_forward(m: *const c_void, d: *mut c_void) -> c_int;
    fn rs_guard_trial_make_data(m: *const c_void) -> c_int;
    fn rs_guard_last_error() -> *const c_char;
}

/// Which MuJoCo function to run guarded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Call {
    /// `mj_step`.
    Step,
    /// `mj_step1`.
    Step1,
    /// `mj_step2`.
    Step2,
    /// `mj_forward`.
    Forward,
}

/// The message of the last fatal error on this thread.
fn last_error() -> String {
    // SAFETY: the shim returns a NUL-terminated thread-local buffer that lives as long as
    // the thread; it is copied out at once.
    unsafe { CStr::from_ptr(rs_guard_last_error()) }
        .to_string_lossy()
        .trim()
        .to_owned()
}

/// Runs `call` on the model and data; `Err(message)` when MuJoCo raised a fatal error
/// (the data is then in an undefined-but-safe-to-reset state).
///
/// # Safety
/// `m` and `d` must be a compiled model and data made for it, both valid for the call, and
/// no MuJoCo callback (`mjcb_*`) that runs Rust code may be installed.
pub(crate) unsafe fn run(call: Call, m: *const mjModel, d: *mut mjData) -> Result<(), String> {
    let (m, d) = (m.cast::<c_void>(), d.cast::<c_void>());
    // SAFETY: as the caller guarantees; the shim only passes the pointers on to MuJoCo.
    let code = unsafe {
        match call {
            Call::Step => rs_guard_step(m, d),
            Call::Step1 => rs_guard_step1(m, d),
            Call::Step2 => rs_guard_step2(m, d),
            Call::Forward => rs_guard_forward(m, d),
        }
    };
    if code == 0 { Ok(()) } else { Err(last_error()) }
}

/// Allocates an `mjData` for `m` and frees it again, guarded: `Err(message)` when MuJoCo
/// cannot (an arena too large, ...), so that the real allocation is not the first try.
///
/// # Safety
/// `m` must be a valid compiled model.
pub(crate) unsafe fn trial_make_data(m: *const mjModel) -> Result<(), String> {
    // SAFETY: as the caller guarantees.
    let code = unsafe { rs_guard_trial_make_data(m.cast::<c_void>()) };
    if code == 0 { Ok(()) } else { Err(last_error()) }
}

#[cfg(test)]
mod tests {
    use crate::sim::Sim;
    use gym_core::Error;
    use mujoco_rs::wrappers::mj_model::MjModel;

    const BALL: &str = "<mujoco><worldbody><body><freejoint/><geom size='0.1'/></body>\
                        <geom type='plane' size='1 1 1'/></worldbody></mujoco>";

    fn model(xml: &str) -> MjModel {
        MjModel::from_xml_string(xml).unwrap()
    }

    #[test]
    fn a_fatal_error_in_a_step_is_a_typed_error_and_the_sim_needs_a_reset() {
        let mut sim = Sim::new(model(BALL)).unwrap();
        sim.step().unwrap();
        // An integrator MuJoCo does not know makes `mj_step` call `mju_error`.
        sim.model_mut().opt_mut().integrator = 99;
        let Err(Error::Simulation(message)) = sim.step() else {
            panic!("expected a simulation error");
        };
        assert!(message.to_string().contains("integrator"), "{message}");
        assert!(sim.failed());
        // Nothing reaches MuJoCo until a reset.
        sim.model_mut().opt_mut().integrator = 0;
        let Err(Error::Simulation(again)) = sim.step() else {
            panic!("expected the earlier error");
        };
        assert!(again.to_string().contains("earlier"), "{again}");
        sim.reset_data();
        assert!(!sim.failed());
        for _ in 0..10 {
            sim.step().unwrap();
        }
        sim.forward().unwrap();
    }

    #[test]
    fn errors_on_other_threads_are_caught_there() {
        let handles: Vec<_> = (0..4)
            .map(|i| {
                std::thread::spawn(move || {
                    let mut sim = Sim::new(model(BALL)).unwrap();
                    for n in 0..50 {
                        if (n + i) % 7 == 0 {
                            sim.model_mut().opt_mut().integrator = 99;
                            assert!(sim.step().is_err());
                            sim.model_mut().opt_mut().integrator = 0;
                            sim.reset_data();
                        } else {
                            sim.step().unwrap();
                        }
                    }
                })
            })
            .collect();
        for h in handles {
            h.join().unwrap();
        }
    }

    #[test]
    fn a_model_that_cannot_step_fails_when_the_sim_is_made() {
        let mut bad = model(BALL);
        bad.opt_mut().integrator = 99;
        assert!(matches!(Sim::new(bad), Err(Error::Model(m)) if m.to_string().contains("trial")));
        // An arena too small for one step ("mj_stackAlloc: out of memory" in MuJoCo).
        let tiny = BALL.replace("<worldbody>", "<size memory='1K'/><worldbody>");
        let Err(Error::Model(message)) = Sim::new(model(&tiny)) else {
            panic!("expected a model error");
        };
        assert!(message.to_string().contains("memory"), "{message}");
    }
}
