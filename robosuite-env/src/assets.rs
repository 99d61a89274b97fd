//! Where robosuite 1.5.2's own model files are: the MJCF of its arenas, robots, grippers,
//! mounts and objects, their meshes and textures, and its controller JSON files.
//!
//! Nothing of robosuite is copied into this repository. The build fetches the PyPI wheel
//! `robosuite==1.5.2` once and unpacks its data into a user cache
//! (`build-support/fetch_robosuite.py`); at run time [`Assets::locate`] looks, in order, at
//! * `$ROBOSUITE_ASSETS`: an existing robosuite install (its `robosuite` package folder,
//!   the `site-packages` folder holding it, or its `robosuite/models/assets` folder);
//! * the cache: `$ROBOSUITE_RS_CACHE`, else `$XDG_CACHE_HOME/robosuite-rs`, else
//!   `~/.cache/robosuite-rs`, each followed by `robosuite-1.5.2/robosuite`;
//! * the cache the build filled (its path is compiled in).
//!
//! A missing or unreadable file is an [`Error::Model`] that names the file and says how to
//! get it back.

use gym_core::{Error, Result};
use std::path::{Path, PathBuf};

/// The robosuite release whose model files are used.
pub const ROBOSUITE_VERSION: &str = "1.5.2";

/// The environment variable that points at an existing robosuite install.
pub const ASSETS_ENV: &str = "ROBOSUITE_ASSETS";

/// How to get the files back, appended to every asset error.
const HOW_TO_FIX: &str = "run `python3 build-support/fetch_robosuite.py` (or rebuild, which runs it), \
     or set ROBOSUITE_ASSETS to a robosuite 1.5.2 install";

/// robosuite's data folders: `models/assets` and `controllers/config` of one robosuite
/// package folder.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Assets {
    package: PathBuf,
}

impl Assets {
    /// Finds robosuite's model files (see the [module docs](self) for where it looks).
    ///
    /// # Errors
    /// [`Error::Model`] when `$ROBOSUITE_ASSETS` is set but holds no robosuite model files,
    /// or when no cache holds them; the message says how to fix it.
    pub fn locate() -> Result<Self> {
        if let Some(dir) = std::env::var_os(ASSETS_ENV) {
            return Self::at(PathBuf::from(dir))
                .map_err(|e| Error::model(format!("{ASSETS_ENV} is set, but {e}")));
        }
        let mut tried = Vec::new();
        for cache in cache_candidates() {
            if let Ok(found) = Self::at(&cache) {
                return Ok(found);
            }
            tried.push(cache.display().to_string());
        }
        Err(Error::model(format!(
            "robosuite {ROBOSUITE_VERSION}'s model files are not in {}; {HOW_TO_FIX}",
            tried.join(" or ")
        )))
    }

    /// robosuite's files under `dir`: a robosuite package folder (`.../robosuite`), the
    /// folder holding it (`site-packages`, or a cache folder), or its `models/assets`
    /// folder.
    ///
    /// # Errors
    /// [`Error::Model`] when none of these holds `models/assets/base.xml`.
    pub fn at(dir: impl AsRef<Path>) -> Result<Self> {
        let dir = dir.as_ref();
        let candidates = [
            dir.to_path_buf(),
            dir.join("robosuite"),
            dir.join("../.."), // dir is .../robosuite/models/assets
        ];
        candidates
            .iter()
            .find(|p| p.join("models/assets/base.xml").is_file())
            .map(|p| Self {
                package: normalize(p),
            })
            .ok_or_else(|| {
                Error::model(format!(
                    "{} holds no robosuite model files (no models/assets/base.xml in it, in \
                     robosuite/ or two folders up)",
                    dir.display()
                ))
            })
    }

    /// The robosuite package folder (`.../robosuite`).
    pub fn package(&self) -> &Path {
        &self.package
    }

    /// robosuite's controller configuration folder, `.../robosuite/controllers/config`.
    pub fn controller_config_dir(&self) -> PathBuf {
        self.package.join("controllers/config")
    }

    /// The model folder, `.../robosuite/models/assets` (robosuite's `assets_root`).
    pub fn root(&self) -> PathBuf {
        self.package.join("models/assets")
    }

    /// The path of a model file relative to the model folder (robosuite's
    /// `xml_path_completion`), checked to exist.
    ///
    /// # Errors
    /// [`Error::Model`] naming the file and how to get it back when it is missing.
    pub fn file(&self, relative: &str) -> Result<PathBuf> {
        let path = self.root().join(relative);
        if path.is_file() {
            Ok(path)
        } else {
            Err(missing(&path))
        }
    }

    /// Reads a model file relative to the model folder.
    ///
    /// # Errors
    /// [`Error::Model`] naming the file when it is missing or unreadable.
    pub fn read(&self, relative: &str) -> Result<String> {
        read_file(&self.file(relative)?)
    }
}

/// Reads a text file robosuite ships, with an asset error when it fails.
///
/// # Errors
/// [`Error::Model`] naming the file and how to get it back.
pub fn read_file(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).map_err(|e| {
        if e.kind() == std::io::ErrorKind::NotFound {
            missing(path)
        } else {
            Error::model(format!("cannot read {}: {e}; {HOW_TO_FIX}", path.display()))
        }
    })
}

fn missing(path: &Path) -> Error {
    Error::model(format!(
        "robosuite's model file {} is missing; {HOW_TO_FIX}",
        path.display()
    ))
}

/// `a/b/../c` → `a/c`, without touching the file system (so links are not resolved).
fn normalize(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// The cache folders to look in, most specific first.
fn cache_candidates() -> Vec<PathBuf> {
    let leaf = format!("robosuite-{ROBOSUITE_VERSION}");
    let mut out = Vec::new();
    if let Some(dir) = std::env::var_os("ROBOSUITE_RS_CACHE") {
        out.push(PathBuf::from(dir).join(&leaf));
    } else if let Some(dir) = std::env::var_os("XDG_CACHE_HOME") {
        out.push(PathBuf::from(dir).join("robosuite-rs").join(&leaf));
    } else if let Some(home) = std::env::var_os("HOME") {
        out.push(PathBuf::from(home).join(".cache/robosuite-rs").join(&leaf));
    }
    if let Some(built) = option_env!("ROBOSUITE_RS_BUILD_ASSETS") {
        let built = PathBuf::from(built);
        if !out.contains(&built) {
            out.push(built);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locate_finds_the_fetched_files_and_at_accepts_three_layouts() {
        let assets = Assets::locate().expect("the build fetched robosuite's model files");
        let root = assets.root();
        assert!(root.join("base.xml").is_file());
        for dir in [
            assets.package().to_path_buf(),
            assets.package().parent().unwrap().to_path_buf(),
            root.clone(),
        ] {
            assert_eq!(
                Assets::at(&dir).unwrap(),
                assets,
                "layout {}",
                dir.display()
            );
        }
        assert!(assets.file("robots/panda/robot.xml").is_ok());
    }

    #[test]
    fn missing_files_and_folders_are_errors_that_say_how_to_fix() {
        let assets = Assets::locate().unwrap();
        let err = assets
            .file("robots/nope/robot.xml")
            .unwrap_err()
            .to_string();
        assert!(err.contains("robots/nope/robot.xml"), "{err}");
        assert!(err.contains("fetch_robosuite.py"), "{err}");
        let err = Assets::at("/definitely/not/here").unwrap_err().to_string();
        assert!(err.contains("/definitely/not/here"), "{err}");
    }
}
