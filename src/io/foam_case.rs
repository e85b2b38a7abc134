//! A runnable OpenFOAM case (#19 "Beyond"): the mesh ([`crate::io::foam`]) in
//! `constant/polyMesh`, plus the minimal `system/` and `0/` files of a steady incompressible
//! external flow (`simpleFoam`, laminar; `potentialFoam` initializes it), for OpenFOAM v1912
//! (Debian's `openfoam`). The boundary conditions come from each family's kind
//! ([`BcKind`]): walls no-slip, far field free-stream, inflow fixed velocity, outflow fixed
//! pressure, symmetry planes symmetric, the extrusion's front and back empty. The case is
//! named by its `.foam` file (`DIR/NAME.foam`, empty: what ParaView opens); the case files go
//! into `DIR`. The free stream is [`FREESTREAM`] along x, the kinematic viscosity [`NU`]:
//! edit `0/U` and `constant/transportProperties` for other flows.

use crate::io::foam::{patch_name, write_polymesh_as};
use crate::io::mesh::{BcKind, Mesh};
use crate::io::{staged, write_atomic};
use crate::{Error, Result};
use std::path::{Path, PathBuf};

/// The free-stream velocity of the case, (x, y, z) (the unit speed along x).
pub const FREESTREAM: [f64; 3] = [1.0, 0.0, 0.0];

/// The kinematic viscosity of the case: Reynolds number 1000 per unit length at the free
/// stream [`FREESTREAM`] (laminar and steady about a unit-chord airfoil).
pub const NU: f64 = 1e-3;

/// The files of a case, relative to its directory, in the order [`write_case`] writes them
/// after the polyMesh.
pub const CASE_FILES: [&str; 7] = [
    "system/controlDict",
    "system/fvSchemes",
    "system/fvSolution",
    "constant/transportProperties",
    "constant/turbulenceProperties",
    "0/U",
    "0/p",
];

/// The boundary conditions of U and p on a patch of kind `bc`, or `None` for a kind that
/// says nothing about the flow (`general`).
fn conditions(bc: BcKind) -> Option<(String, &'static str)> {
    let u = format!(
        "uniform ({} {} {})",
        FREESTREAM[0], FREESTREAM[1], FREESTREAM[2]
    );
    Some(match bc {
        BcKind::Wall => ("type noSlip;".into(), "type zeroGradient;"),
        BcKind::Farfield => (
            format!("type freestreamVelocity; freestreamValue {u};"),
            "type freestreamPressure; freestreamValue uniform 0;",
        ),
        BcKind::Inflow => (format!("type fixedValue; value {u};"), "type zeroGradient;"),
        BcKind::Outflow => (
            format!("type inletOutlet; inletValue uniform (0 0 0); value {u};"),
            "type fixedValue; value uniform 0;",
        ),
        BcKind::Symmetry => ("type symmetry;".into(), "type symmetry;"),
        BcKind::Empty => ("type empty;".into(), "type empty;"),
        BcKind::Other => return None,
    })
}

/// An OpenFOAM dictionary file's header.
fn header(class: &str, location: &str, object: &str) -> String {
    format!(
        "/*--------------------------------*- C++ -*----------------------------------*\\\n\
         | written by ellipgrid                                                      |\n\
         \\*---------------------------------------------------------------------------*/\n\
         FoamFile\n{{\n    version     2.0;\n    format      ascii;\n    class       {class};\n    \
         location    \"{location}\";\n    object      {object};\n}}\n\n"
    )
}

const CONTROL_DICT: &str = "application     simpleFoam;\nstartFrom       latestTime;\n\
startTime       0;\nstopAt          endTime;\nendTime         2000;\ndeltaT          1;\n\
writeControl    timeStep;\nwriteInterval   100;\npurgeWrite      0;\nwriteFormat     ascii;\n\
writePrecision  8;\nwriteCompression off;\ntimeFormat      general;\ntimePrecision   6;\n\
runTimeModifiable true;\n";

const FV_SCHEMES: &str = "ddtSchemes\n{\n    default         steadyState;\n}\n\n\
gradSchemes\n{\n    default         Gauss linear;\n}\n\n\
divSchemes\n{\n    default         none;\n    div(phi,U)      bounded Gauss upwind;\n    \
div((nuEff*dev2(T(grad(U))))) Gauss linear;\n    div(div(phi,U)) Gauss linear;\n}\n\n\
laplacianSchemes\n{\n    default         Gauss linear limited corrected 0.33;\n}\n\n\
interpolationSchemes\n{\n    default         linear;\n}\n\n\
snGradSchemes\n{\n    default         limited corrected 0.33;\n}\n";

const FV_SOLUTION: &str = "solvers\n{\n    p\n    {\n        solver          GAMG;\n        \
smoother        GaussSeidel;\n        tolerance       1e-07;\n        relTol          0.05;\n    }\n\n    \
Phi\n    {\n        $p;\n        relTol          0.01;\n    }\n\n    \
U\n    {\n        solver          smoothSolver;\n        smoother        GaussSeidel;\n        \
nSweeps         2;\n        tolerance       1e-08;\n        relTol          0.1;\n    }\n}\n\n\
SIMPLE\n{\n    nNonOrthogonalCorrectors 2;\n    residualControl\n    {\n        \
p               1e-6;\n        U               1e-7;\n    }\n}\n\n\
potentialFlow\n{\n    nNonOrthogonalCorrectors 3;\n}\n\n\
relaxationFactors\n{\n    fields\n    {\n        p               0.3;\n    }\n    equations\n    {\n        \
U               0.5;\n    }\n}\n";

/// Writes the case `case_file` (`DIR/NAME.foam`): the polyMesh of `mesh` (in OpenFOAM's
/// `binary` format if asked) in `DIR/constant/polyMesh`, the dictionaries of
/// [`CASE_FILES`] and the empty `NAME.foam`, all or none. Returns the files written.
///
/// # Errors
/// [`Error::Input`] naming the families whose kind is `general` (give them `bc = "wall"`,
/// `"farfield"`, … in the case file or the `.conn` file: no flow condition can be guessed
/// for them), and those of [`write_polymesh_as`].
pub fn write_case(case_file: &Path, mesh: &Mesh, binary: bool) -> Result<Vec<PathBuf>> {
    let place = case_file.display().to_string();
    let mut u_bcs = String::new();
    let mut p_bcs = String::new();
    let mut unknown = Vec::new();
    for (family, bc) in mesh.families.iter().zip(&mesh.bcs) {
        let name = patch_name(family);
        match conditions(*bc) {
            Some((u, p)) => {
                u_bcs.push_str(&format!("    {name}\n    {{\n        {u}\n    }}\n"));
                p_bcs.push_str(&format!("    {name}\n    {{\n        {p}\n    }}\n"));
            }
            None => unknown.push(format!("'{family}'")),
        }
    }
    if !unknown.is_empty() {
        return Err(Error::input(
            place,
            format!(
                "an OpenFOAM case needs a boundary condition for every family: {} {} of kind \
                 general; give each a bc = \"wall\", \"farfield\", \"inflow\", \"outflow\" or \
                 \"symmetry\" in the case file (or the .conn file's last section)",
                unknown.join(", "),
                if unknown.len() == 1 { "is" } else { "are" },
            ),
        ));
    }
    let dir = match case_file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let u = format!(
        "uniform ({} {} {})",
        FREESTREAM[0], FREESTREAM[1], FREESTREAM[2]
    );
    let bodies = [
        header("dictionary", "system", "controlDict") + CONTROL_DICT,
        header("dictionary", "system", "fvSchemes") + FV_SCHEMES,
        header("dictionary", "system", "fvSolution") + FV_SOLUTION,
        header("dictionary", "constant", "transportProperties")
            + &format!("transportModel  Newtonian;\n\nnu              {NU:e};\n"),
        header("dictionary", "constant", "turbulenceProperties") + "simulationType  laminar;\n",
        header("volVectorField", "0", "U")
            + &format!(
                "dimensions      [0 1 -1 0 0 0 0];\n\ninternalField   {u};\n\n\
                 boundaryField\n{{\n{u_bcs}}}\n"
            ),
        header("volScalarField", "0", "p")
            + &format!(
                "dimensions      [0 2 -2 0 0 0 0];\n\ninternalField   uniform 0;\n\n\
                 boundaryField\n{{\n{p_bcs}}}\n"
            ),
    ];
    staged(|| {
        let polymesh = dir.join("constant").join("polyMesh");
        write_polymesh_as(&polymesh, mesh, binary)?;
        let mut written: Vec<PathBuf> = ["points", "faces", "owner", "neighbour", "boundary"]
            .iter()
            .map(|f| polymesh.join(f))
            .collect();
        for (file, body) in CASE_FILES.iter().zip(&bodies) {
            let path = dir.join(file);
            let sub = path.parent().expect("case files are in a folder");
            std::fs::create_dir_all(sub).map_err(|e| Error::io(sub, e))?;
            write_atomic(&path, |w| w.write_all(body.as_bytes()))?;
            written.push(path);
        }
        write_atomic(case_file, |_| Ok(()))?;
        written.push(case_file.to_path_buf());
        Ok(written)
    })
}
