//! A runnable OpenFOAM case (#19 "Beyond"): the mesh ([`crate::io::foam`]) in
//! `constant/polyMesh`, plus the minimal `system/` and `0/` files of a steady incompressible
//! external flow (`simpleFoam`, laminar, consistent SIMPLE, started from the uniform free
//! stream), for OpenFOAM v1912 (Debian's `openfoam`). The boundary conditions come from each
//! family's kind ([`BcKind`]): walls no-slip, far field free-stream, inflow fixed velocity,
//! outflow fixed pressure, symmetry planes symmetric, the extrusion's front and back empty.
//! The case is named by its `.foam` file (`DIR/NAME.foam`, empty: what ParaView opens); the
//! case files go into `DIR`. The free stream (speed, angle of attack, sideslip) and the
//! kinematic viscosity are a [`Flow`] (`[flow]` in a case file, flags of `convert`).
//!
//! No `potentialFoam` start: the potential flow about a sharp trailing edge has no Kutta
//! condition and leaves a jet through the trailing edge that the viscous iteration removes
//! only very slowly in the wall-resolved cells there (docs/SOLVER_MESHES.md,
//! "OpenFOAM case: why the first version stalled").

use crate::io::foam::{patch_name, write_polymesh_as};
use crate::io::mesh::{BcKind, Mesh};
use crate::io::{staged, write_atomic};
use crate::{Error, Result};
use std::path::{Path, PathBuf};

/// The free stream and viscosity of a case. The velocity is `speed` along the direction of
/// the angle of attack `alpha_deg`, in the x–y plane of a planar grid and in the x–z plane of
/// a volume grid, turned out of that plane towards +y by the sideslip `sideslip_deg`
/// (volumes only): `speed (cos α, sin α, 0)` planar, `speed (cos α cos β, sin β, sin α cos β)`
/// in 3D. The default is the unit speed along x and `nu` = 1e-3: Reynolds number 1000 per
/// unit length (laminar and steady about a unit-chord airfoil).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flow {
    /// Free-stream speed (> 0).
    pub speed: f64,
    /// Angle of attack, degrees (|α| < 90).
    pub alpha_deg: f64,
    /// Sideslip, degrees (|β| < 90; volume grids only).
    pub sideslip_deg: f64,
    /// Kinematic viscosity (> 0).
    pub nu: f64,
}

impl Default for Flow {
    fn default() -> Self {
        Flow {
            speed: 1.0,
            alpha_deg: 0.0,
            sideslip_deg: 0.0,
            nu: 1e-3,
        }
    }
}

/// The flow as given (a case file's `[flow]`, `convert`'s flags): every value optional; `nu`
/// or else `reynolds` (with the reference `length`, default 1) sets the viscosity.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FlowInput {
    /// Free-stream speed.
    pub speed: Option<f64>,
    /// Angle of attack, degrees.
    pub alpha: Option<f64>,
    /// Sideslip, degrees.
    pub sideslip: Option<f64>,
    /// Kinematic viscosity.
    pub nu: Option<f64>,
    /// Reynolds number `speed * length / nu`.
    pub reynolds: Option<f64>,
    /// Reference length of `reynolds`.
    pub length: Option<f64>,
}

impl Flow {
    /// The flow `input` asks for, checked: speed, viscosity, Reynolds number and length
    /// finite and > 0, angles finite and within ±90°, `nu` and `reynolds` not both, `length`
    /// only with `reynolds`. `place` names where the values were given and `key` spells a
    /// key's name there (`alpha` in a case file, `--alpha` on the command line).
    ///
    /// # Errors
    /// [`Error::Input`] naming `place` and the key of the first bad value.
    pub fn from_input(
        input: &FlowInput,
        place: &str,
        key: impl Fn(&str) -> String,
    ) -> Result<Flow> {
        let bad = |name: &str, v: f64, why: &str| {
            Error::input(place, format!("{} = {v}: {why}", key(name)))
        };
        let positive = |name: &str, v: Option<f64>| match v {
            Some(x) if !(x.is_finite() && x > 0.0) => Err(bad(name, x, "must be a number > 0")),
            _ => Ok(v),
        };
        let angle = |name: &str, v: Option<f64>| match v {
            Some(x) if !(x.is_finite() && x.abs() < 90.0) => Err(bad(
                name,
                x,
                "must be an angle in degrees between -90 and 90 (the free stream enters \
                 through the far field ahead)",
            )),
            _ => Ok(v.unwrap_or(0.0)),
        };
        let speed = positive("speed", input.speed)?.unwrap_or(1.0);
        let alpha_deg = angle("alpha", input.alpha)?;
        let sideslip_deg = angle("sideslip", input.sideslip)?;
        let nu = positive("nu", input.nu)?;
        let reynolds = positive("reynolds", input.reynolds)?;
        let length = positive("length", input.length)?;
        let nu = match (nu, reynolds, length) {
            (Some(_), Some(_), _) => {
                return Err(Error::input(
                    place,
                    format!(
                        "{} and {} both set the viscosity: give one",
                        key("nu"),
                        key("reynolds")
                    ),
                ))
            }
            (_, None, Some(l)) => {
                return Err(bad(
                    "length",
                    l,
                    &format!(
                        "the reference length of {}, which is not given",
                        key("reynolds")
                    ),
                ))
            }
            (Some(nu), None, None) => nu,
            (None, Some(re), l) => speed * l.unwrap_or(1.0) / re,
            (None, None, _) => Flow::default().nu,
        };
        Ok(Flow {
            speed,
            alpha_deg,
            sideslip_deg,
            nu,
        })
    }

    /// The free-stream velocity (x, y, z) of a planar grid (`planar`) or a volume grid.
    pub fn velocity(&self, planar: bool) -> [f64; 3] {
        let (a, b) = (self.alpha_deg.to_radians(), self.sideslip_deg.to_radians());
        let v = self.speed;
        if planar {
            [v * a.cos(), v * a.sin(), 0.0]
        } else {
            [v * a.cos() * b.cos(), v * b.sin(), v * a.sin() * b.cos()]
        }
    }
}

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

/// The boundary conditions of U and p on a patch of kind `bc` with the free stream `u` (an
/// OpenFOAM uniform vector), or `None` for a kind that
/// says nothing about the flow (`general`).
fn conditions(bc: BcKind, u: &str) -> Option<(String, &'static str)> {
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
smoother        GaussSeidel;\n        tolerance       1e-07;\n        relTol          0.01;\n    }\n\n    \
U\n    {\n        solver          smoothSolver;\n        smoother        GaussSeidel;\n        \
nSweeps         2;\n        tolerance       1e-08;\n        relTol          0.1;\n    }\n}\n\n\
SIMPLE\n{\n    consistent      yes;\n    nNonOrthogonalCorrectors 1;\n    residualControl\n    {\n        \
p               1e-5;\n        U               2e-4;\n    }\n}\n\n\
relaxationFactors\n{\n    fields\n    {\n        p               1;\n    }\n    equations\n    {\n        \
U               0.7;\n    }\n}\n";

/// Writes the case `case_file` (`DIR/NAME.foam`) of the flow `flow`: the polyMesh of `mesh`
/// (in OpenFOAM's `binary` format if asked) in `DIR/constant/polyMesh`, the dictionaries of
/// [`CASE_FILES`] and the empty `NAME.foam`, all or none. A mesh with an `empty` family (a
/// planar grid extruded) is planar: its flow lies in the x–y plane. Returns the files written.
///
/// # Errors
/// [`Error::Input`] naming the families whose kind is `general` (give them `bc = "wall"`,
/// `"farfield"`, … in the case file or the `.conn` file: no flow condition can be guessed
/// for them), a sideslip on a planar grid, and those of [`write_polymesh_as`].
pub fn write_case(
    case_file: &Path,
    mesh: &Mesh,
    binary: bool,
    flow: &Flow,
) -> Result<Vec<PathBuf>> {
    let place = case_file.display().to_string();
    let planar = mesh.bcs.iter().any(|b| matches!(b, BcKind::Empty));
    if planar && flow.sideslip_deg != 0.0 {
        return Err(Error::input(
            place,
            format!(
                "sideslip = {}: a planar grid's flow lies in its plane; the sideslip turns \
                 the flow of volume grids (use alpha)",
                flow.sideslip_deg
            ),
        ));
    }
    let [ux, uy, uz] = flow.velocity(planar);
    let u = format!("uniform ({ux} {uy} {uz})");
    let mut u_bcs = String::new();
    let mut p_bcs = String::new();
    let mut unknown = Vec::new();
    for (family, bc) in mesh.families.iter().zip(&mesh.bcs) {
        let name = patch_name(family);
        match conditions(*bc, &u) {
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
    let nu = flow.nu;
    let bodies = [
        header("dictionary", "system", "controlDict") + CONTROL_DICT,
        header("dictionary", "system", "fvSchemes") + FV_SCHEMES,
        header("dictionary", "system", "fvSolution") + FV_SOLUTION,
        header("dictionary", "constant", "transportProperties")
            + &format!("transportModel  Newtonian;\n\nnu              {nu:e};\n"),
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_velocity_turns_by_alpha_in_the_plane_and_by_the_sideslip_out_of_it() {
        let f = |alpha_deg, sideslip_deg| Flow {
            speed: 2.0,
            alpha_deg,
            sideslip_deg,
            nu: 1e-3,
        };
        let close = |a: [f64; 3], b: [f64; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-15);
        let h = 3f64.sqrt();
        assert_eq!(Flow::default().velocity(true), [1.0, 0.0, 0.0]);
        assert!(close(f(30.0, 0.0).velocity(true), [h, 1.0, 0.0]));
        assert!(close(f(30.0, 0.0).velocity(false), [h, 0.0, 1.0]));
        assert!(close(f(0.0, 30.0).velocity(false), [h, 1.0, 0.0]));
        assert!(close(f(60.0, 60.0).velocity(false), [0.5, h, 0.5 * h]));
    }

    #[test]
    fn the_viscosity_comes_from_nu_or_the_reynolds_number() {
        let key = |k: &str| k.to_string();
        let input = |nu, reynolds, length| FlowInput {
            speed: Some(3.0),
            nu,
            reynolds,
            length,
            ..FlowInput::default()
        };
        let nu = |i| Flow::from_input(&i, "here", key).unwrap().nu;
        assert_eq!(nu(input(None, None, None)), 1e-3);
        assert_eq!(nu(input(Some(0.25), None, None)), 0.25);
        assert_eq!(nu(input(None, Some(300.0), None)), 0.01);
        assert_eq!(nu(input(None, Some(300.0), Some(2.0))), 0.02);
        let e = Flow::from_input(&input(None, None, Some(2.0)), "here", key).unwrap_err();
        assert!(e.to_string().contains("length = 2"), "{e}");
    }
}
