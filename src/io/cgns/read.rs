//! Reading CGNS files back: zones as blocks (in the order of their ordinals), 1-to-1
//! connections and point-range boundary conditions as a connectivity.

use super::{c, File, NameBuf};
use crate::io::connectivity::{BcKind, ConnFile, Range};
use crate::io::Block;
use crate::{Error, Grid2, Grid3, Result};
use cgns_sys::*;
use std::ffi::CStr;
use std::os::raw::{c_int, c_void};
use std::path::Path;

fn name_of(b: &NameBuf) -> String {
    // SAFETY: the library NUL-terminates names within 33 bytes.
    unsafe { CStr::from_ptr(b.as_ptr()) }
        .to_string_lossy()
        .into_owned()
}

/// Reads the first base of a CGNS file: its structured zones as blocks (cell dimension 2 and
/// physical dimension 2: planar; 2 and 3: surfaces; 3: volumes) and the connectivity (each
/// interface once, point-range boundary conditions by family).
///
/// # Errors
/// [`Error::Format`] naming the file for anything but structured zones with X, Y (Z)
/// coordinates and point-range BCs, or a failed library call.
pub fn read_cgns(path: &Path) -> Result<(Vec<(String, Block)>, ConnFile)> {
    let _one_at_a_time = super::library();
    let meta = std::fs::metadata(path).map_err(|e| Error::io(path, e))?;
    if meta.is_dir() {
        return Err(Error::input(path.display().to_string(), "is a directory"));
    }
    // Zone sizes come from the file: their coordinates must fit in it (no compression is
    // written or expected), so a hostile header cannot make us allocate without bound.
    let mut budget = meta.len();
    let f = File::open(path, CG_MODE_READ)?;
    let ok = |ier, what: &str| f.ok(ier, what);
    let bad = |m: String| Error::format(path, m);
    let (mut nb, mut cell, mut phys) = (0, 0, 0);
    let mut bname: NameBuf = [0; 33];
    // SAFETY (every call below): valid out-pointers and buffers of the sizes CGNS fills.
    ok(unsafe { cg_nbases(f.fd, &mut nb) }, "bases")?;
    if nb < 1 {
        return Err(bad("no base".into()));
    }
    ok(
        unsafe { cg_base_read(f.fd, 1, bname.as_mut_ptr(), &mut cell, &mut phys) },
        "base",
    )?;
    let (cell, phys) = (cell as usize, phys as usize);
    if !matches!((cell, phys), (2, 2) | (2, 3) | (3, 3)) {
        return Err(bad(format!(
            "cell dimension {cell}, physical dimension {phys}"
        )));
    }
    let mut nz = 0;
    ok(unsafe { cg_nzones(f.fd, 1, &mut nz) }, "zones")?;
    let mut blocks = Vec::new();
    let mut zone_names = Vec::new();
    let mut conn = ConnFile::default();
    let mut raw_links = Vec::new();
    let mut ordinals = Vec::new();
    for z in 1..=nz {
        let mut zname: NameBuf = [0; 33];
        let mut size = [0 as c_int; 9];
        let mut zt = 0;
        ok(unsafe { cg_zone_type(f.fd, 1, z, &mut zt) }, "zone type")?;
        ok(
            unsafe { cg_zone_read(f.fd, 1, z, zname.as_mut_ptr(), size.as_mut_ptr()) },
            "zone",
        )?;
        let name = name_of(&zname);
        if zt != ZoneType_t_Structured {
            return Err(bad(format!("zone '{name}' is not structured")));
        }
        let mut dims = [1usize; 3];
        for d in 0..cell {
            dims[d] = usize::try_from(size[d]).unwrap_or(0);
            if dims[d] < 2 {
                return Err(bad(format!(
                    "zone '{name}': {} nodes along a direction",
                    size[d]
                )));
            }
        }
        let n: usize = dims.iter().product();
        let bytes = (n as u64).saturating_mul(8 * phys as u64);
        if bytes > budget {
            return Err(bad(format!(
                "zone '{name}': {} × {} × {} nodes do not fit in the file",
                dims[0], dims[1], dims[2]
            )));
        }
        budget -= bytes;
        let rmin = [1 as c_int; 3];
        let rmax = [size[0], size[1], size[2]];
        let mut coords = Vec::new();
        for cname in ["CoordinateX", "CoordinateY", "CoordinateZ"]
            .iter()
            .take(phys)
        {
            let mut buf = vec![0f64; n];
            ok(
                unsafe {
                    cg_coord_read(
                        f.fd,
                        1,
                        z,
                        c(cname).as_ptr(),
                        DataType_t_RealDouble,
                        rmin.as_ptr(),
                        rmax.as_ptr(),
                        buf.as_mut_ptr() as *mut c_void,
                    )
                },
                &format!("zone '{name}', {cname}"),
            )?;
            coords.push(buf);
        }
        let block = match (cell, phys) {
            (2, 2) => Block::Planar(Grid2::from_coords(
                dims[0],
                dims[1],
                [
                    std::mem::take(&mut coords[0]),
                    std::mem::take(&mut coords[1]),
                ],
            )),
            (2, _) => Block::Surface(Grid2::from_coords(
                dims[0],
                dims[1],
                [
                    std::mem::take(&mut coords[0]),
                    std::mem::take(&mut coords[1]),
                    std::mem::take(&mut coords[2]),
                ],
            )),
            _ => Block::Volume(Grid3::from_coords(
                dims[0],
                dims[1],
                dims[2],
                [
                    std::mem::take(&mut coords[0]),
                    std::mem::take(&mut coords[1]),
                    std::mem::take(&mut coords[2]),
                ],
            )),
        };
        let mut ordinal = z;
        let zpath = c(&format!("/{}/{name}", name_of(&bname)));
        // SAFETY: as above; a zone without an ordinal keeps its place.
        if unsafe { cg_gopath(f.fd, zpath.as_ptr()) } == CG_OK as c_int {
            let mut o = 0;
            if unsafe { cg_ordinal_read(&mut o) } == CG_OK as c_int && o > 0 {
                ordinal = o;
            }
        }
        ordinals.push(ordinal);
        zone_names.push(name.clone());
        blocks.push((name.clone(), block));
        let corner = |v: &[c_int], k: usize| -> [usize; 3] {
            let mut x = [1usize; 3];
            for d in 0..cell {
                x[d] = v[k * cell + d].max(0) as usize;
            }
            x
        };
        let mut n1 = 0;
        ok(unsafe { cg_n1to1(f.fd, 1, z, &mut n1) }, "1to1 count")?;
        for i in 1..=n1 {
            let (mut cn, mut dn): (NameBuf, NameBuf) = ([0; 33], [0; 33]);
            let (mut r, mut d, mut t) = ([0 as c_int; 6], [0 as c_int; 6], [0 as c_int; 3]);
            ok(
                unsafe {
                    cg_1to1_read(
                        f.fd,
                        1,
                        z,
                        i,
                        cn.as_mut_ptr(),
                        dn.as_mut_ptr(),
                        r.as_mut_ptr(),
                        d.as_mut_ptr(),
                        t.as_mut_ptr(),
                    )
                },
                &format!("zone '{name}', 1to1 {i}"),
            )?;
            raw_links.push((
                z as usize,
                [corner(&r, 0), corner(&r, 1)],
                name_of(&dn),
                [corner(&d, 0), corner(&d, 1)],
            ));
        }
        let mut nbc = 0;
        ok(unsafe { cg_nbocos(f.fd, 1, z, &mut nbc) }, "BC count")?;
        for bc in 1..=nbc {
            let mut bcname: NameBuf = [0; 33];
            let (mut bt, mut pst, mut np) = (0, 0, 0 as c_int);
            let mut ni = [0 as c_int; 3];
            let (mut nl, mut ndt, mut nds) = (0 as c_int, 0, 0);
            ok(
                unsafe {
                    cg_boco_info(
                        f.fd,
                        1,
                        z,
                        bc,
                        bcname.as_mut_ptr(),
                        &mut bt,
                        &mut pst,
                        &mut np,
                        ni.as_mut_ptr(),
                        &mut nl,
                        &mut ndt,
                        &mut nds,
                    )
                },
                &format!("zone '{name}', BC {bc}"),
            )?;
            let bcn = name_of(&bcname);
            if pst != PointSetType_t_PointRange || np != 2 {
                return Err(bad(format!(
                    "zone '{name}', BC '{bcn}': only point ranges are read"
                )));
            }
            let mut pts = [0 as c_int; 6];
            ok(
                unsafe { cg_boco_read(f.fd, 1, z, bc, pts.as_mut_ptr(), std::ptr::null_mut()) },
                &format!("zone '{name}', BC '{bcn}'"),
            )?;
            let gopath = c(&format!("/{}/{name}/ZoneBC/{bcn}", name_of(&bname)));
            let mut fam: NameBuf = [0; 33];
            // SAFETY: as above; a BC without a family name keeps its own name.
            let family = if unsafe { cg_gopath(f.fd, gopath.as_ptr()) } == CG_OK as c_int
                && unsafe { cg_famname_read(fam.as_mut_ptr()) } == CG_OK as c_int
            {
                name_of(&fam)
            } else {
                bcn.clone()
            };
            let id = match conn.families.iter().find(|f| f.1 == family) {
                Some(f) => f.0,
                None => {
                    let id = conn.families.len() + 1;
                    conn.families.push((id, family));
                    id
                }
            };
            conn.patches
                .push(((z as usize, corner(&pts, 0), corner(&pts, 1)), id));
        }
    }
    read_family_bcs(f.fd, &mut conn);
    // Each interface is stored on both sides: keep the side whose (zone, range) comes first.
    for (z, r, donor, d) in raw_links {
        let dz = 1 + zone_names
            .iter()
            .position(|n| *n == donor)
            .ok_or_else(|| bad(format!("1to1 donor zone '{donor}' not found")))?;
        let a: Range = (z, r[0], r[1]);
        let b: Range = (dz, d[0], d[1]);
        let lo = [0, 1, 2].map(|k| d[0][k].min(d[1][k]));
        let hi = [0, 1, 2].map(|k| d[0][k].max(d[1][k]));
        if (z, r) <= (dz, [lo, hi]) {
            conn.interfaces.push([a, b]);
        }
    }
    // Blocks in the order of their ordinals; zone numbers in the connectivity follow.
    let mut order: Vec<usize> = (0..blocks.len()).collect();
    order.sort_by_key(|&k| (ordinals[k], k));
    let mut new_of = vec![0; blocks.len()];
    for (new, &old) in order.iter().enumerate() {
        new_of[old] = new + 1;
    }
    let mut slots: Vec<Option<(String, Block)>> = blocks.into_iter().map(Some).collect();
    let blocks = order
        .iter()
        .map(|&k| slots[k].take().expect("a permutation"))
        .collect();
    for r in conn.interfaces.iter_mut().flatten() {
        r.0 = new_of[r.0 - 1];
    }
    for (r, _) in conn.patches.iter_mut() {
        r.0 = new_of[r.0 - 1];
    }
    Ok((blocks, conn))
}

/// The base's families' `FamilyBC`s: those other than the one a family's name suggests are
/// kept as given ([`ConnFile::bcs`]). Families without a `FamilyBC` keep the guess.
fn read_family_bcs(fd: c_int, conn: &mut ConnFile) {
    let mut n: c_int = 0;
    // SAFETY: the file is open; out-parameters are valid for the calls' writes.
    if unsafe { cg_nfamilies(fd, 1, &mut n) } != CG_OK as c_int {
        return;
    }
    for fam in 1..=n {
        let (mut name, mut bcname): (NameBuf, NameBuf) = ([0; 33], [0; 33]);
        let (mut nboco, mut ngeo): (c_int, c_int) = (0, 0);
        // SAFETY: as above; names are 33-byte buffers (CGNS names hold 32 characters).
        let read = unsafe { cg_family_read(fd, 1, fam, name.as_mut_ptr(), &mut nboco, &mut ngeo) };
        if read != CG_OK as c_int || nboco < 1 {
            continue;
        }
        let mut t: BCType_t = BCType_t_BCTypeNull;
        // SAFETY: as above.
        if unsafe { cg_fambc_read(fd, 1, fam, 1, bcname.as_mut_ptr(), &mut t) } != CG_OK as c_int {
            continue;
        }
        let family = name_of(&name);
        let kind = super::bc_kind(t);
        if let Some(f) = conn.families.iter().find(|f| f.1 == family) {
            if kind != BcKind::of(&family) {
                conn.bcs.push((f.0, kind));
            }
        }
    }
}
