//! Converts an OBJ (with its `.mtl` materials) to binary glTF:
//!
//!     cargo run -p rt-scene --bin obj2glb -- IN.obj OUT.glb
//!
//! The mesh is written as the loader reads it (triangulated, with its
//! normals, one primitive per material; `Kd` as base colour, `Ke` as
//! emissive), so the `.glb` renders as the OBJ does. Exit status 2 for a
//! bad OBJ (one line naming the file, the line and the problem), 1 if the
//! output cannot be written.

use std::path::Path;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [input, output] = &args[..] else {
        eprintln!("usage: obj2glb IN.obj OUT.glb");
        return ExitCode::from(2);
    };
    // Through `load_flat`, whose boundary turns a loader's panic into one
    // line naming the file.
    let loaded = match rt_scene::load_flat(Path::new(input)) {
        Ok((l, _)) => l,
        Err(e) => {
            eprintln!("obj2glb: {e}");
            return ExitCode::from(2);
        }
    };
    let name = Path::new(input).file_stem().map_or("mesh".into(), |s| s.to_string_lossy().into_owned());
    let glb = rt_scene::glb::from_obj(&loaded, &name).to_glb();
    if let Err(e) = std::fs::write(output, &glb) {
        eprintln!("obj2glb: {output}: {e}");
        return ExitCode::FAILURE;
    }
    println!(
        "{output}: {} triangles, {} materials, {} bytes",
        loaded.mesh.indices.len(),
        loaded.materials.len(),
        glb.len()
    );
    ExitCode::SUCCESS
}
