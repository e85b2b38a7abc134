//! CGNS output and input (HDF5) through the CGNS library itself (`cgns-sys`, Debian's
//! `libcgns-dev`; the `cgns` feature): one base (cell dimension 2 or 3), a structured zone per
//! block with double-precision coordinates (`NormalizedByUnknownDimensional`, length
//! exponents: the grid's units are the case's), `GridConnectivity1to1` for every interface on
//! both sides (point range, donor range, transform), and a `ZoneBC` per boundary patch
//! (vertex point range, `FamilySpecified`, the family name) with the families in the base,
//! each with the `FamilyBC` its name suggests ([`BcKind`]). Names are cut to CGNS's 32
//! characters and made unique.

use crate::io::connectivity::ConnFile;
use crate::io::mesh::{one_to_one, BcKind};
use crate::io::Block;
use crate::{Error, Result};
use cgns_sys::*;
use std::ffi::{CStr, CString};
use std::os::raw::{c_char, c_int, c_void};
use std::path::Path;

mod read;
pub use read::read_cgns;

/// CGNS's name buffers: 32 characters and a NUL.
type NameBuf = [c_char; 33];

/// The CGNS mid-level library keeps global state (its open-file table, the `cg_goto`
/// position, the error message) and is not thread-safe: every use of it holds this lock for
/// the whole file, so that files written or read at once (outputs in parallel, tests) do not
/// interleave their calls.
static LIBRARY: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Holds [`LIBRARY`] (a panic elsewhere while holding it leaves no library state to fear).
fn library() -> std::sync::MutexGuard<'static, ()> {
    LIBRARY.lock().unwrap_or_else(|p| p.into_inner())
}

/// An open CGNS file; closed on drop.
struct File<'a> {
    path: &'a Path,
    fd: c_int,
}

impl Drop for File<'_> {
    fn drop(&mut self) {
        // SAFETY: fd came from a successful cg_open and is closed once.
        unsafe { cg_close(self.fd) };
    }
}

impl<'a> File<'a> {
    /// The error of a failed call, with the library's message.
    fn err(&self, what: &str) -> Error {
        // SAFETY: cg_get_error returns a NUL-terminated static buffer.
        let msg = unsafe { CStr::from_ptr(cg_get_error()) }
            .to_string_lossy()
            .into_owned();
        Error::format(self.path, format!("CGNS {what}: {msg}"))
    }

    fn ok(&self, ier: c_int, what: &str) -> Result<()> {
        if ier == CG_OK as c_int {
            Ok(())
        } else {
            Err(self.err(what))
        }
    }

    /// Goes to node `index` of label `child` inside the first `parent` of zone `z`.
    fn goto_in_zone(
        &self,
        base: c_int,
        z: c_int,
        parent: &str,
        child: &str,
        index: c_int,
    ) -> Result<()> {
        let (zone, parent, child, end) = (c("Zone_t"), c(parent), c(child), c("end"));
        // SAFETY: label/index pairs as cg_goto reads them, C strings alive across the call.
        let ier = unsafe {
            cg_goto(
                self.fd,
                base,
                zone.as_ptr(),
                z,
                parent.as_ptr(),
                1 as c_int,
                child.as_ptr(),
                index,
                end.as_ptr(),
            )
        };
        self.ok(ier, "goto")
    }

    fn open(path: &'a Path, mode: u32) -> Result<File<'a>> {
        let name = CString::new(path.as_os_str().as_encoded_bytes())
            .map_err(|_| Error::input(path.display().to_string(), "a NUL in the file name"))?;
        let mut fd = 0;
        // SAFETY: valid C string and out-pointer.
        let ier = unsafe {
            if mode == CG_MODE_WRITE {
                cg_set_file_type(CG_FILE_HDF5 as c_int);
            }
            cg_open(name.as_ptr(), mode as c_int, &mut fd)
        };
        if ier != CG_OK as c_int {
            let f = File { path, fd: -1 };
            let e = f.err("open");
            std::mem::forget(f);
            return Err(e);
        }
        Ok(File { path, fd })
    }
}

/// A name cut to 32 characters (at a character boundary), unique among `taken`.
fn unique(name: &str, taken: &mut Vec<String>) -> CString {
    let clean: String = name
        .chars()
        .map(|c| if c == '/' || c.is_control() { '_' } else { c })
        .collect();
    let cut = |s: &str, n: usize| -> String {
        let mut out = String::new();
        for c in s.chars() {
            if out.len() + c.len_utf8() > n {
                break;
            }
            out.push(c);
        }
        out
    };
    let mut s = cut(&clean, 32);
    let mut k = 2;
    while taken.contains(&s) || s.is_empty() {
        let tail = format!("_{k}");
        s = format!("{}{tail}", cut(&clean, 32 - tail.len()));
        k += 1;
    }
    taken.push(s.clone());
    CString::new(s).expect("no NUL after cleaning")
}

fn c(s: &str) -> CString {
    CString::new(s).expect("static name")
}

/// CGNS's family boundary condition for a family's.
fn bc_type(bc: BcKind) -> BCType_t {
    match bc {
        BcKind::Wall => BCType_t_BCWall,
        BcKind::Symmetry => BCType_t_BCSymmetryPlane,
        BcKind::Farfield => BCType_t_BCFarfield,
        BcKind::Inflow => BCType_t_BCInflow,
        BcKind::Outflow => BCType_t_BCOutflow,
        BcKind::Empty | BcKind::Other => BCType_t_BCGeneral,
    }
}

/// The boundary condition a CGNS `BCType_t` stands for (wall kinds are walls, the rest
/// general).
fn bc_kind(t: BCType_t) -> BcKind {
    #[allow(non_upper_case_globals)]
    match t {
        BCType_t_BCWall
        | BCType_t_BCWallViscous
        | BCType_t_BCWallViscousHeatFlux
        | BCType_t_BCWallViscousIsothermal
        | BCType_t_BCWallInviscid => BcKind::Wall,
        BCType_t_BCSymmetryPlane => BcKind::Symmetry,
        BCType_t_BCFarfield => BcKind::Farfield,
        BCType_t_BCInflow | BCType_t_BCInflowSubsonic | BCType_t_BCInflowSupersonic => {
            BcKind::Inflow
        }
        BCType_t_BCOutflow | BCType_t_BCOutflowSubsonic | BCType_t_BCOutflowSupersonic => {
            BcKind::Outflow
        }
        _ => BcKind::Other,
    }
}

/// Writes `blocks` (all of one kind) with their connectivity as a CGNS/HDF5 file, atomically.
///
/// # Errors
/// [`Error::Input`] for blocks of mixed kinds, a connectivity that does not fit the blocks,
/// more than 2³¹ nodes in a block; [`Error::Format`] with the library's message if a CGNS call
/// fails; [`Error::Io`].
pub fn write_cgns(path: &Path, blocks: &[(String, Block)], conn: &ConnFile) -> Result<()> {
    let _one_at_a_time = library();
    let place = path.display().to_string();
    let Some((_, first)) = blocks.first() else {
        return Err(Error::input(place, "no blocks"));
    };
    if let Some((n, b)) = blocks.iter().find(|(_, b)| b.kind() != first.kind()) {
        return Err(Error::input(
            place,
            format!(
                "block '{n}' is {}: a CGNS base holds blocks of one kind",
                b.kind()
            ),
        ));
    }
    let (cell, phys) = match first {
        Block::Planar(_) => (2, 2),
        Block::Surface(_) => (2, 3),
        Block::Volume(_) => (3, 3),
    };
    for (n, b) in blocks {
        if b.nnodes() > i32::MAX as usize {
            return Err(Error::input(
                place,
                format!("block '{n}': more than 2³¹ nodes"),
            ));
        }
    }
    // Both sides of every interface, checked before anything is written.
    let mut links = Vec::new();
    for (n, [a, b]) in conn.interfaces.iter().enumerate() {
        links.push(one_to_one(&place, blocks, n, a, b)?);
        links.push(one_to_one(&place, blocks, n, b, a)?);
    }
    crate::io::write_atomic_path(path, |tmp| {
        let f = File::open(tmp, CG_MODE_WRITE)?;
        write_base(&f, blocks, conn, &links, cell, phys)
    })
}

fn write_base(
    f: &File,
    blocks: &[(String, Block)],
    conn: &ConnFile,
    links: &[crate::io::mesh::OneToOne],
    cell: usize,
    phys: usize,
) -> Result<()> {
    let mut base = 0;
    let ok = |ier, what: &str| f.ok(ier, what);
    let end = c("end");
    // SAFETY (every call below): C strings live across the call, out-pointers are valid,
    // arrays are as long as the library reads for the base's dimensions.
    ok(
        unsafe {
            cg_base_write(
                f.fd,
                c("Base").as_ptr(),
                cell as c_int,
                phys as c_int,
                &mut base,
            )
        },
        "base",
    )?;
    ok(unsafe { cg_goto(f.fd, base, end.as_ptr()) }, "goto base")?;
    ok(
        unsafe { cg_dataclass_write(DataClass_t_NormalizedByUnknownDimensional) },
        "data class",
    )?;
    let mut fam_names = Vec::new();
    let families: Vec<CString> = conn
        .families
        .iter()
        .map(|(_, n)| unique(n, &mut fam_names))
        .collect();
    for (cn, (id, name)) in families.iter().zip(&conn.families) {
        let (mut fi, mut bi) = (0, 0);
        ok(
            unsafe { cg_family_write(f.fd, base, cn.as_ptr(), &mut fi) },
            "family",
        )?;
        ok(
            unsafe {
                cg_fambc_write(
                    f.fd,
                    base,
                    fi,
                    c("FamBC").as_ptr(),
                    bc_type(conn.bc(*id, name)),
                    &mut bi,
                )
            },
            "family BC",
        )?;
    }
    let mut zone_names = Vec::new();
    let zones: Vec<CString> = blocks
        .iter()
        .map(|(n, _)| unique(n, &mut zone_names))
        .collect();
    let names = ["CoordinateX", "CoordinateY", "CoordinateZ"];
    for (bi, (_, b)) in blocks.iter().enumerate() {
        let dims = b.dims();
        let mut size = vec![0 as c_int; 3 * cell];
        for d in 0..cell {
            size[d] = dims[d] as c_int;
            size[cell + d] = dims[d] as c_int - 1;
        }
        let mut z = 0;
        ok(
            unsafe {
                cg_zone_write(
                    f.fd,
                    base,
                    zones[bi].as_ptr(),
                    size.as_ptr(),
                    ZoneType_t_Structured,
                    &mut z,
                )
            },
            "zone",
        )?;
        // The library lists zones by name; the ordinal keeps the blocks' order.
        ok(
            unsafe { cg_goto(f.fd, base, c("Zone_t").as_ptr(), z, end.as_ptr()) },
            "goto zone",
        )?;
        ok(unsafe { cg_ordinal_write(bi as c_int + 1) }, "ordinal")?;
        for (k, name) in names.iter().enumerate().take(phys) {
            let mut ci = 0;
            let data = b.coord(k);
            ok(
                unsafe {
                    cg_coord_write(
                        f.fd,
                        base,
                        z,
                        DataType_t_RealDouble,
                        c(name).as_ptr(),
                        data.as_ptr() as *const c_void,
                        &mut ci,
                    )
                },
                "coordinates",
            )?;
            let exps: [f64; 5] = [0.0, 1.0, 0.0, 0.0, 0.0];
            f.goto_in_zone(base, z, "GridCoordinates_t", "DataArray_t", ci)?;
            ok(
                unsafe {
                    cg_exponents_write(DataType_t_RealDouble, exps.as_ptr() as *const c_void)
                },
                "exponents",
            )?;
        }
        let flat = |r: &[[usize; 3]; 2]| -> Vec<c_int> {
            let mut v = Vec::with_capacity(2 * cell);
            for corner in r {
                v.extend(corner[..cell].iter().map(|&x| x as c_int));
            }
            v
        };
        let mut taken = Vec::new();
        for (n, l) in links.iter().enumerate().filter(|(_, l)| l.block == bi) {
            let (range, donor) = (flat(&l.range), flat(&l.donor_range));
            let name = unique(&format!("1to1_{}", n / 2 + 1), &mut taken);
            let mut ii = 0;
            ok(
                unsafe {
                    cg_1to1_write(
                        f.fd,
                        base,
                        z,
                        name.as_ptr(),
                        zones[l.donor].as_ptr(),
                        range.as_ptr(),
                        donor.as_ptr(),
                        l.transform.as_ptr(),
                        &mut ii,
                    )
                },
                "1to1 connection",
            )?;
        }
        for (n, (r, id)) in conn
            .patches
            .iter()
            .enumerate()
            .filter(|(_, p)| p.0 .0 == bi + 1)
        {
            let fam = conn
                .families
                .iter()
                .position(|f| f.0 == *id)
                .ok_or_else(|| {
                    Error::input(
                        f.path.display().to_string(),
                        format!("patch {}: family {id} is not in the family list", n + 1),
                    )
                })?;
            let lo = [0, 1, 2].map(|k| r.1[k].min(r.2[k]));
            let hi = [0, 1, 2].map(|k| r.1[k].max(r.2[k]));
            let pts = flat(&[lo, hi]);
            let name = unique(&format!("{}_{}", n + 1, conn.families[fam].1), &mut taken);
            let mut bc = 0;
            ok(
                unsafe {
                    cg_boco_write(
                        f.fd,
                        base,
                        z,
                        name.as_ptr(),
                        BCType_t_FamilySpecified,
                        PointSetType_t_PointRange,
                        2,
                        pts.as_ptr(),
                        &mut bc,
                    )
                },
                "boundary condition",
            )?;
            ok(
                unsafe { cg_boco_gridlocation_write(f.fd, base, z, bc, GridLocation_t_Vertex) },
                "grid location",
            )?;
            f.goto_in_zone(base, z, "ZoneBC_t", "BC_t", bc)?;
            ok(
                unsafe { cg_famname_write(families[fam].as_ptr()) },
                "family name",
            )?;
        }
    }
    Ok(())
}
