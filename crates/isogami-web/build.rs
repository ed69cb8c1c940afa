//! Builds the browser front end (`web/` at the repository root) with npm and esbuild and
//! embeds the result: `npm ci` when `web/node_modules` is missing or older than the lock
//! file, then `node build.mjs $OUT_DIR/web`, then a generated `assets.rs` listing every
//! built file for `include_bytes!`. `ISOGAMI_WEB_DIST=<folder>` embeds an already built
//! folder instead (packaging without npm).

use std::fs::{self, File};
use std::path::{Path, PathBuf};
use std::process::Command;

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("set by cargo"));
    println!("cargo:rerun-if-env-changed=ISOGAMI_WEB_DIST");
    let given = std::env::var_os("ISOGAMI_WEB_DIST");
    let dist = match &given {
        Some(dir) => PathBuf::from(dir),
        None => {
            let web = manifest.join("../../web");
            let web = web.canonicalize().unwrap_or_else(|_| {
                fail(&format!(
                    "the front end folder {} is missing",
                    web.display()
                ))
            });
            build_front_end(&web, &out.join("web"))
        }
    };
    let mut files = Vec::new();
    list_files(&dist, &dist, &mut files);
    files.sort();
    if !files.iter().any(|(name, _)| name == "index.html") {
        fail(&format!("{} has no index.html", dist.display()));
    }
    let mut code = String::from(
        "/// Every file of the built front end: (path relative to the site root, bytes).\n",
    );
    code.push_str("pub static ASSETS: &[(&str, &[u8])] = &[\n");
    for (name, path) in &files {
        // Watch a given folder's files. Never the files this script just built: they are
        // newer than the moment cargo records for the run, so cargo would find the script
        // stale on every build and rebuild and relink everything after it (the sources in
        // web/ are what is watched then, in build_front_end).
        if given.is_some() {
            println!("cargo:rerun-if-changed={}", path.display());
        }
        code.push_str(&format!(
            "    ({name:?}, include_bytes!({:?})),\n",
            path.display().to_string()
        ));
    }
    code.push_str("];\n");
    fs::write(out.join("assets.rs"), code).expect("write assets.rs");
}

/// Runs npm and the bundler; returns the output folder.
fn build_front_end(web: &Path, dist: &Path) -> PathBuf {
    for input in ["src", "build.mjs", "package.json", "package-lock.json"] {
        println!("cargo:rerun-if-changed={}", web.join(input).display());
    }
    let lock_file = web.join("package-lock.json");
    let stamp = web.join("node_modules/.package-lock.json");
    // Two cargo profiles building at once must not run `npm ci` in the same folder together.
    let guard = File::create(web.join(".npm-ci.lock")).expect("create web/.npm-ci.lock");
    guard.lock().expect("lock web/.npm-ci.lock");
    if is_older(&stamp, &lock_file) {
        run(
            Command::new("npm")
                .args(["ci", "--no-audit", "--no-fund", "--loglevel=error"])
                .current_dir(web),
            "npm ci (node and npm must be installed)",
        );
    }
    let _ = fs::remove_dir_all(dist);
    run(
        Command::new("node")
            .arg("build.mjs")
            .arg(dist)
            .current_dir(web),
        "node build.mjs",
    );
    drop(guard);
    dist.to_path_buf()
}

/// True when `a` is missing or was modified before `b`.
fn is_older(a: &Path, b: &Path) -> bool {
    let modified = |p: &Path| fs::metadata(p).and_then(|m| m.modified()).ok();
    match (modified(a), modified(b)) {
        (Some(ta), Some(tb)) => ta < tb,
        _ => true,
    }
}

fn run(cmd: &mut Command, what: &str) {
    match cmd.status() {
        Ok(s) if s.success() => {}
        Ok(s) => fail(&format!("{what} failed ({s})")),
        Err(e) => fail(&format!("{what} could not start: {e}")),
    }
}

fn list_files(root: &Path, dir: &Path, out: &mut Vec<(String, PathBuf)>) {
    let entries =
        fs::read_dir(dir).unwrap_or_else(|e| fail(&format!("cannot read {}: {e}", dir.display())));
    for entry in entries {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            list_files(root, &path, out);
        } else {
            let name = path
                .strip_prefix(root)
                .expect("under root")
                .to_string_lossy()
                .replace('\\', "/");
            out.push((name, path));
        }
    }
}

fn fail(message: &str) -> ! {
    panic!("isogami-web front end: {message}");
}
