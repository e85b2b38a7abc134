//! Malformed settings and sizes (issue #17): every numeric [solver] setting is checked
//! (finite, in range), unknown keys are errors everywhere, including in tables whose type
//! takes no keys, and node counts are checked (overflow-safe, an absolute cap, the memory the
//! job needs against the memory available) before anything is allocated. Each case exits 2
//! with a message naming the file and the key or block, without a panic and without writing
//! anything.

mod common;
use common::*;
use std::fs;

#[test]
fn solver_settings_out_of_range_exit_2_naming_the_key() {
    let base = square_case(5, 5);
    for (setting, key) in [
        ("linear_forcing = nan", "linear_forcing"),
        ("linear_forcing = -0.5", "linear_forcing"),
        ("linear_forcing = 1.5", "linear_forcing"),
        ("tolerance = nan", "tolerance"),
        ("tolerance = -1e-10", "tolerance"),
        ("tolerance = 0.0", "tolerance"),
        ("tolerance = inf", "tolerance"),
        ("linear_tolerance = 2.0", "linear_tolerance"),
        ("max_steps = 0", "max_steps"),
        ("max_steps = 1000000000000", "max_steps"),
        ("linear_max_iter = 0", "linear_max_iter"),
        ("anderson = 1000", "anderson"),
    ] {
        let case = format!("{base}\n[solver]\n{setting}\n");
        rejects(&case, &["bad.toml", "[solver]", key]);
    }
    // In range: accepted.
    let d = tempfile::tempdir().unwrap();
    let case = format!("{base}\n[solver]\nlinear_forcing = 0.0\nanderson = 3\ntolerance = 1e-9\n");
    fs::write(d.path().join("ok.toml"), case).unwrap();
    let o = ellipgrid(d.path(), &["run", "ok.toml", "-o", "out.x", "-q"]);
    assert!(o.status.success(), "{}", text(&o));
}

#[test]
fn smooth_tolerance_is_checked() {
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("c.toml"), square_case(5, 5)).unwrap();
    let o = ellipgrid(d.path(), &["run", "c.toml", "-o", "g.x", "-q"]);
    assert!(o.status.success(), "{}", text(&o));
    let o = ellipgrid(
        d.path(),
        &["smooth", "g.x", "-o", "s.x", "--tolerance", "NaN"],
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("tolerance"), "{}", text(&o));
    assert!(!d.path().join("s.x").exists());
}

#[test]
fn unknown_keys_of_key_less_types_are_errors() {
    // A uniform distribution takes no spacing: the key would be silently ignored.
    let case = one_block_case(
        5,
        5,
        "curve = { type = \"line\", from = [0, 0], to = [0, 1] }\ndistribution = { type = \"uniform\", first = 1e-4 }",
        "curve = { type = \"line\", from = [1, 0], to = [1, 1] }",
        "curve = { type = \"line\", from = [0, 0], to = [1, 0] }",
        "curve = { type = \"line\", from = [0, 1], to = [1, 1] }",
    );
    rejects(&case, &["bad.toml", "first"]);
    // The tanh bump surface takes no keys.
    let case = "[[block]]\nname = \"s\"\nkind = \"surface\"\nni = 5\nnj = 5\n\
                surface = { type = \"tanh_bump\", amplitude = 2 }\n";
    rejects(case, &["bad.toml", "amplitude"]);
}

/// `ellipgrid` with the available memory set to `gb` gigabytes.
fn with_memory(dir: &std::path::Path, gb: &str, args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_ellipgrid"))
        .args(args)
        .current_dir(dir)
        .env("ELLIPGRID_MEMORY_GB", gb)
        .output()
        .unwrap()
}

#[test]
fn node_counts_are_checked_before_anything_is_allocated() {
    // Overflowing and huge counts: a 2D block, an edge of a topology, a volume, an inline
    // Hermite net whose ni × nj wraps.
    let huge = square_case(5, 5).replace("nj = 5", "nj = 9223372036854775807");
    rejects(
        &huge,
        &["bad.toml", "block 'b'", "more than the 2147483648 nodes"],
    );
    let big = square_case(5, 5)
        .replace("ni = 5", "ni = 100000")
        .replace("nj = 5", "nj = 100000");
    rejects(&big, &["block 'b'", "100000 × 100000 nodes"]);
    let naca = std::fs::read_to_string(root().join("examples/naca0012_ogrid.toml")).unwrap();
    let edge = naca.replacen("n = 49", "n = 4611686018427387904", 1);
    rejects(&edge, &["edge 'cut_te'", "more than the"]);
    let vol = std::fs::read_to_string(root().join("examples/volume_warped_cube.toml")).unwrap();
    let vol = vol.replacen("nj = 25", "nj = 1000000000", 1);
    rejects(&vol, &["volume", "25 × 1000000000 × 25 nodes"]);
    let net = "[[block]]\nname = \"s\"\nkind = \"surface\"\nni = 5\nnj = 5\n\
               surface = { type = \"hermite_net\", ni = 4294967296, nj = 4294967296, \
               points = [[0, 0, 0]] }\n[block.E1]\n[block.E2]\n[block.E3]\n[block.E4]\n";
    rejects(net, &["1 points given", "4294967296 × 4294967296"]);

    // The memory a job needs against the memory available.
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("c.toml"), square_case(301, 301)).unwrap();
    let o = with_memory(d.path(), "0.01", &["run", "c.toml", "-o", "g.x"]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(
        t.contains("c.toml") && t.contains("needs ~") && t.contains("ELLIPGRID_MEMORY_GB"),
        "{t}"
    );
    assert!(!d.path().join("g.x").exists());
    let o = with_memory(d.path(), "1", &["run", "c.toml", "-o", "g.x", "-q"]);
    assert!(o.status.success(), "{}", text(&o));

    // step grid --ni/--nj: a 30000² face needs ~630 GB.
    let net = root().join("data/wing_pylon_net.x");
    let o = ellipgrid(
        d.path(),
        &["step", "export", net.to_str().unwrap(), "-o", "net.step"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let o = with_memory(
        d.path(),
        "8",
        &[
            "step", "grid", "net.step", "--face", "1", "--ni", "30000", "--nj", "30000", "-o",
            "f.x",
        ],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(t.contains("needs ~") && t.contains("--ni"), "{t}");
    assert!(!d.path().join("f.x").exists());
}

#[test]
fn hostile_vtk_headers_exit_2_without_a_panic() {
    let d = tempfile::tempdir().unwrap();
    let good = "<?xml version=\"1.0\"?>\n<VTKFile type=\"StructuredGrid\" version=\"0.1\">\
                <StructuredGrid WholeExtent=\"0 1 0 1 0 0\"><Piece Extent=\"0 1 0 1 0 0\">\
                <Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\
                0 0 0 1 0 0 0 1 0 1 1 0</DataArray></Points></Piece></StructuredGrid></VTKFile>";
    for (name, body, needle) in [
        (
            "root.vts",
            "WholeExtent=\"0 1\"<VTKFile type=\"StructuredGrid\">".to_string(),
            "WholeExtent",
        ),
        (
            "wide.vts",
            good.replace(
                "\"0 1 0 1 0 0\"",
                "\"-9223372036854775808 9223372036854775807 0 1 0 0\"",
            ),
            "WholeExtent",
        ),
        ("nan.vts", good.replace("1 1 0<", "NaN 1 0<"), "non-finite"),
    ] {
        std::fs::write(d.path().join(name), body).unwrap();
        let o = ellipgrid(d.path(), &["convert", name, "out.x"]);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "{name}: {t}");
        assert!(t.contains(name) && t.contains(needle), "{name}: {t}");
        assert!(!t.contains("panicked"), "{t}");
        assert!(!d.path().join("out.x").exists());
    }
    std::fs::write(d.path().join("good.vts"), good).unwrap();
    let o = ellipgrid(d.path(), &["convert", "good.vts", "out.x"]);
    assert!(o.status.success(), "{}", text(&o));
}

#[test]
fn hostile_step_files_exit_2_without_a_panic_or_a_runaway_allocation() {
    let d = tempfile::tempdir().unwrap();
    let net = root().join("data/wing_pylon_net.x");
    let o = ellipgrid(
        d.path(),
        &["step", "export", net.to_str().unwrap(), "-o", "net.step"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let good = fs::read_to_string(d.path().join("net.step")).unwrap();
    let o = ellipgrid(d.path(), &["step", "list", "net.step"]);
    assert!(o.status.success(), "{}", text(&o));
    let huge = good.replacen("(4, 3, 3, 3", "(4, 2147483647, 3, 3", 1);
    let deep = good.replacen(
        "('', 3, 3,",
        &format!("('', 3, 3, {}0{},", "(".repeat(10_000), ")".repeat(10_000)),
        1,
    );
    let inf = good.replacen("(0.0, 0.02083333", "(0.0, 1.E400, 0.02083333", 1);
    for (name, body, needle) in [
        ("huge.step", huge, "multiplicity 2147483647"),
        ("deep.step", deep, "nested deeper"),
        ("inf.step", inf, "the STEP reader failed"),
    ] {
        assert_ne!(body, good, "{name}: the edit did not apply");
        fs::write(d.path().join(name), body).unwrap();
        let o = ellipgrid(d.path(), &["step", "list", name]);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "{name}: {t}");
        assert!(t.contains(name) && t.contains(needle), "{name}: {t}");
        assert!(!t.contains("panicked"), "{name}: {t}");
    }
}

#[cfg(unix)]
#[test]
fn endless_special_files_and_directories_are_refused_early() {
    let d = tempfile::tempdir().unwrap();
    for args in [
        &["run", "/dev/zero", "-o", "z.x"][..],
        &["convert", "/dev/zero", "z.x"],
        &["step", "list", "/dev/zero"],
        &["check", "/dev/zero"],
    ] {
        let o = ellipgrid(d.path(), args);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {t}");
        assert!(
            t.contains("/dev/zero") && t.contains("more than"),
            "{args:?}: {t}"
        );
    }
    let o = ellipgrid(d.path(), &["run", ".", "-o", "z.x"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("directory"), "{}", text(&o));
    let left: Vec<_> = fs::read_dir(d.path()).unwrap().collect();
    assert!(left.is_empty(), "{left:?}");
}

/// A volume case (`examples/volume_warped_cube.toml`) at `n`³ nodes with `linear`.
fn cube(n: usize, linear: &str) -> String {
    std::fs::read_to_string(root().join("examples/volume_warped_cube.toml"))
        .unwrap()
        .replace("= 25\n", &format!("= {n}\n"))
        .replace("linear = \"bicgstab\"", &format!("linear = \"{linear}\""))
}

#[test]
fn direct_solves_too_large_for_the_memory_are_refused_before_they_start() {
    // An 81³ volume with the direct solver: faer's LU would need ~90 GB (it used to fail
    // inside the factorization, reported as a singular matrix). Refused at once, exit 2.
    rejects(
        &cube(81, "direct"),
        &[
            "bad.toml",
            "needs ~",
            "for the LU of linear = \"direct\"",
            "\"bicgstab\" for a volume block",
            "available",
        ],
    );
    // The same block with an iterative solver passes the check.
    let d = tempfile::tempdir().unwrap();
    let path = d.path().join("c.toml");
    let ok = ellipgrid::case::LoadedCase::parse(&cube(81, "bicgstab"), &path);
    assert!(ok.is_ok(), "{:?}", ok.err());

    // smooth: a 301² planar block regridded with --linear direct needs ~0.37 GB for the LU.
    let g = ellipgrid::Grid2::<2>::from_fn(301, 301, |i, j| [i as f64, j as f64 + 0.1 * i as f64]);
    let fmt = ellipgrid::io::plot3d::Plot3dFormat {
        two_d: true,
        ..Default::default()
    };
    ellipgrid::io::plot3d::write_plot3d(
        &d.path().join("g.x"),
        &[ellipgrid::io::Block::from(g)],
        &fmt,
        None,
    )
    .unwrap();
    let o = with_memory(
        d.path(),
        "0.1",
        &["smooth", "g.x", "-o", "s.x", "--linear", "direct"],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(
        t.contains("g.x") && t.contains("for the LU of linear = \"direct\""),
        "{t}"
    );
    assert!(!d.path().join("s.x").exists());
}

#[cfg(unix)]
#[test]
fn a_direct_solve_that_runs_out_of_memory_says_so() {
    // The estimate overridden (ELLIPGRID_MEMORY_GB=100) and the address space capped at
    // 1.2 GB: a 37³ volume's LU (~1.8 GB) fails inside faer, which is reported as memory,
    // not as a singular matrix, with exit 2 and nothing written.
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("c.toml"), cube(37, "direct")).unwrap();
    let bin = env!("CARGO_BIN_EXE_ellipgrid");
    let o = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v 1200000 && exec '{bin}' run c.toml -o g.x -q"
        ))
        .current_dir(d.path())
        .env("ELLIPGRID_MEMORY_GB", "100")
        .output()
        .unwrap();
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(
        t.contains("volume 'cube'")
            && t.contains("the direct LU of 42875 unknowns ran out of memory")
            && !t.contains("singular"),
        "{t}"
    );
    assert!(!d.path().join("g.x").exists());
}

#[test]
fn step_files_too_large_for_the_reader_are_refused_before_it_starts() {
    // The STEP reader holds the whole file as a syntax tree (~17–27 bytes per byte of the
    // file, 10 s per million entities): entity counts, list lengths and the memory it would
    // need are checked on the text first.
    let d = tempfile::tempdir().unwrap();
    let head = "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n";
    let tail = "ENDSEC;\nEND-ISO-10303-21;\n";
    let many = format!("{head}{}{tail}", "#1=A();".repeat(5_000_001));
    let long = format!(
        "{head}#1=CARTESIAN_POINT('',({}0.));\n{tail}",
        "0.,".repeat(1_000_000)
    );
    for (name, body, memory, needle) in [
        (
            "many.step",
            many,
            None,
            "more than 5000000 entity instances",
        ),
        (
            "long.step",
            long.clone(),
            None,
            "line 6: a list of more than 1000000 items",
        ),
        (
            "big.step",
            long,
            Some("0.05"),
            "needs ~0.090 GB, the machine has 0.050 GB",
        ),
    ] {
        fs::write(d.path().join(name), body).unwrap();
        let args = ["step", "list", name];
        let o = match memory {
            Some(gb) => with_memory(d.path(), gb, &args),
            None => ellipgrid(d.path(), &args),
        };
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "{name}: {t}");
        assert!(t.contains(name) && t.contains(needle), "{name}: {t}");
        assert!(!t.contains("panicked"), "{name}: {t}");
    }
}
