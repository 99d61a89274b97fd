//! Provides the MuJoCo 3.17.0 shared library that mujoco-rs links against, and robosuite
//! 1.5.2's model files.
//!
//! By default the library is fetched once from the PyPI wheel `mujoco==3.17.0` into
//! `<target>/<profile>/mujoco-3.17.0/lib` (inside the target folder, so `cargo run` and
//! `cargo test` put it on the loader path, and the rpath in `.cargo/config.toml` finds it
//! for binaries run directly). Set `MUJOCO_DYNAMIC_LINK_DIR` to use an existing MuJoCo
//! 3.17.0 instead.
//!
//! It also fetches robosuite 1.5.2's model files (the PyPI wheel `robosuite==1.5.2`,
//! unpacked by `build-support/fetch_robosuite.py` into the user cache that
//! `src/assets.rs` reads at run time) unless `ROBOSUITE_ASSETS` points at an
//! existing robosuite install.

use std::path::{Path, PathBuf};
use std::process::Command;

const VERSION: &str = "3.17.0";

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-changed=../build-support/fetch_mujoco.py");
    println!("cargo::rerun-if-env-changed=MUJOCO_DYNAMIC_LINK_DIR");
    println!("cargo::rerun-if-changed=../build-support/fetch_robosuite.py");
    println!("cargo::rerun-if-env-changed=ROBOSUITE_ASSETS");
    println!("cargo::rerun-if-env-changed=ROBOSUITE_RS_CACHE");
    println!("cargo::rerun-if-env-changed=XDG_CACHE_HOME");
    if std::env::var_os("DOCS_RS").is_some() {
        return;
    }
    fetch_robosuite_assets();
    build_guard();
    let lib_dir = match std::env::var_os("MUJOCO_DYNAMIC_LINK_DIR") {
        Some(dir) => user_library(PathBuf::from(dir)),
        None => fetched_library(),
    };
    let lib = lib_dir.join(format!("libmujoco.so.{VERSION}"));
    settle(&lib);
    println!("cargo::rerun-if-changed={}", lib.display());
    println!("cargo::rustc-link-search=native={}", lib_dir.display());
    println!("cargo::rustc-link-lib=dylib=mujoco");
    println!(
        "cargo::rustc-env=ROBOSUITE_MUJOCO_LIB_DIR={}",
        lib_dir.display()
    );
}

/// Compiles the C shim that turns MuJoCo's fatal errors into error codes
/// (`csrc/guard.c`, explained in `src/sim/guard.rs`).
fn build_guard() {
    println!("cargo::rerun-if-changed=csrc/guard.c");
    cc::Build::new()
        .file("csrc/guard.c")
        .std("c11")
        .warnings(true)
        .compile("robosuite_guard");
}

/// Checks a library folder the user chose.
fn user_library(dir: PathBuf) -> PathBuf {
    if !dir.join(format!("libmujoco.so.{VERSION}")).is_file() || !dir.join("libmujoco.so").exists()
    {
        fail(&format!(
            "MUJOCO_DYNAMIC_LINK_DIR={} holds no libmujoco.so.{VERSION} with its libmujoco.so link; \
             point it at the lib/ folder of MuJoCo {VERSION}, or unset it to fetch the library",
            dir.display()
        ));
    }
    dir
}

/// Fetches the library into the profile folder unless it is already there.
fn fetched_library() -> PathBuf {
    let out_dir = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    // OUT_DIR is <target>/<profile>/build/<package>-<hash>/out.
    let profile_dir = out_dir
        .ancestors()
        .nth(3)
        .expect("OUT_DIR lies inside the target folder");
    let dest = profile_dir.join(format!("mujoco-{VERSION}"));
    let lib_dir = dest.join("lib");
    if lib_dir.join(format!("libmujoco.so.{VERSION}")).is_file() {
        return lib_dir;
    }
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../build-support/fetch_mujoco.py");
    let python = std::env::var("PYTHON").unwrap_or_else(|_| "python3".to_owned());
    println!("cargo::rerun-if-env-changed=PYTHON");
    let status = Command::new(&python).arg(&script).arg(&dest).status();
    match status {
        Ok(s) if s.success() => lib_dir,
        Ok(_) => fail("fetching MuJoCo failed (see the fetch_mujoco line above)"),
        Err(e) => fail(&format!(
            "cannot run `{python}` to fetch MuJoCo {VERSION} ({e}); install python3 with pip, \
             or set MUJOCO_DYNAMIC_LINK_DIR to the lib/ folder of MuJoCo {VERSION}"
        )),
    }
}

/// Fetches robosuite's model files into the user cache unless `ROBOSUITE_ASSETS` is set
/// (the run-time lookup then uses that install; a wrong path is reported when an env is made).
fn fetch_robosuite_assets() {
    if std::env::var_os("ROBOSUITE_ASSETS").is_some() {
        return;
    }
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../build-support/fetch_robosuite.py");
    let python = std::env::var("PYTHON").unwrap_or_else(|_| "python3".to_owned());
    match Command::new(&python).arg(&script).output() {
        Ok(out) if out.status.success() => {
            let dest = String::from_utf8_lossy(&out.stdout).trim().to_owned();
            settle(&Path::new(&dest).join(".robosuite-rs-complete"));
            println!("cargo::rerun-if-changed={dest}/.robosuite-rs-complete");
            println!("cargo::rustc-env=ROBOSUITE_RS_BUILD_ASSETS={dest}");
        }
        Ok(out) => fail(&format!(
            "fetching robosuite's model files failed: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        )),
        Err(e) => fail(&format!(
            "cannot run `{python}` to fetch robosuite 1.5.2's model files ({e}); install python3 \
             with pip, or set ROBOSUITE_ASSETS to an existing robosuite 1.5.2 install"
        )),
    }
}

/// Gives `path`, a file this script watches with `rerun-if-changed` and may have just
/// created (a fetch), a modification time no later than `build.rs`'s. Cargo compares it with
/// the time this run started: a file made during the run would read as changed, so the
/// next build (the next profile's, or the next package's build sharing this one) would run
/// the script again and rebuild the crate and everything above it.
fn settle(path: &Path) {
    let reference = Path::new(env!("CARGO_MANIFEST_DIR")).join("build.rs");
    let times = (
        std::fs::metadata(path).and_then(|m| m.modified()),
        std::fs::metadata(reference).and_then(|m| m.modified()),
    );
    if let (Ok(modified), Ok(earlier)) = times
        && modified > earlier
        && let Ok(file) = std::fs::File::options().write(true).open(path)
    {
        // Best effort: a file that keeps its time costs one extra rebuild, nothing else.
        let _ = file.set_modified(earlier);
    }
}

fn fail(message: &str) -> ! {
    eprintln!("robosuite-env: {message}");
    std::process::exit(1);
}
