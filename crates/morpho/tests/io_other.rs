//! Point, polygon and volume formats: round trips, the real data in /work/shared/data, and
//! malformed input (errors, never panics or huge allocations).

mod common;
use common::data_dir;
use morpho::geom::Point2;
use morpho::io;
use morpho::mesh::{Column, PointSet, Polygon, Polyline, Shapes2};
use morpho::volume::{Axes, DType, Volume};
use std::io::Write;
use std::path::{Path, PathBuf};

fn p(x: f64, y: f64) -> Point2 {
    Point2::new(x, y)
}

fn put(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn gz(bytes: &[u8]) -> Vec<u8> {
    let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    e.write_all(bytes).unwrap();
    e.finish().unwrap()
}

fn zlib(bytes: &[u8]) -> Vec<u8> {
    let mut e = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
    e.write_all(bytes).unwrap();
    e.finish().unwrap()
}

fn err_of<T: std::fmt::Debug>(r: morpho::Result<T>) -> String {
    r.expect_err("expected an error").to_string()
}

// ------------------------------------------------------------------------------------------
// round trips

#[test]
fn points_csv_and_xyz_round_trip_with_columns() {
    let dir = tempfile::tempdir().unwrap();
    let pts = PointSet {
        dim: 3,
        coords: vec![
            0.1,
            -2.5e-7,
            3.0,
            1e300,
            0.3333333333333333,
            -0.0,
            5.0,
            6.0,
            7.0,
        ],
        columns: vec![
            Column {
                name: "zinc".into(),
                values: vec![1022.0, f64::NAN, 0.125],
            },
            Column {
                name: "component".into(),
                values: vec![0.0, 1.0, 2.0],
            },
        ],
    };
    for name in ["a.csv", "a.xyz"] {
        let path = dir.path().join(name);
        io::write_points(&path, &pts).unwrap();
        let back = io::read_points(&path).unwrap();
        assert_eq!(back.dim, 3, "{name}");
        assert_eq!(back.coords, pts.coords, "{name}");
        assert_eq!(back.columns.len(), 2, "{name}");
        for (a, b) in back.columns.iter().zip(&pts.columns) {
            assert_eq!(a.name, b.name);
            for (x, y) in a.values.iter().zip(&b.values) {
                assert!(x == y || (x.is_nan() && y.is_nan()), "{name} {x} {y}");
            }
        }
    }
    // 2D points with a column: CSV keeps it
    let p2 = PointSet {
        dim: 2,
        coords: vec![1.0, 2.0, 3.0, 4.0],
        columns: vec![Column {
            name: "value with space".into(),
            values: vec![1.0, 2.0],
        }],
    };
    let path = dir.path().join("b.csv");
    io::write_points(&path, &p2).unwrap();
    assert_eq!(io::read_points(&path).unwrap(), p2);
}

fn shapes_fixture() -> Shapes2 {
    Shapes2 {
        polygons: vec![
            Polygon {
                rings: vec![
                    vec![p(0., 0.), p(10., 0.), p(10., 10.), p(0., 10.)],
                    vec![p(2., 2.), p(2., 4.), p(4., 4.), p(4., 2.)],
                    vec![p(6., 6.), p(6., 8.), p(8., 8.)],
                ],
            },
            Polygon {
                rings: vec![vec![p(20., 0.), p(21., 0.), p(20.5, 0.1)]],
            },
        ],
        polylines: vec![Polyline {
            points: vec![p(0.1, 0.2), p(0.3, 0.4), p(-1.0, 1e-9)],
            closed: false,
        }],
    }
}

#[test]
fn polygons_csv_and_geojson_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let sh = shapes_fixture();
    // CSV keeps everything in order
    let path = dir.path().join("s.csv");
    io::write_shapes2(&path, &sh).unwrap();
    assert_eq!(io::read_shapes2(&path).unwrap(), sh);
    // single polygon with holes: x,y,ring layout
    let one = Shapes2 {
        polygons: vec![sh.polygons[0].clone()],
        polylines: vec![],
    };
    io::write_shapes2(&path, &one).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.starts_with("x,y,ring\n"), "{text}");
    assert_eq!(io::read_shapes2(&path).unwrap(), one);
    // GeoJSON: same shapes, rings possibly reversed (outer CCW, holes CW)
    let path = dir.path().join("s.geojson");
    io::write_shapes2(&path, &sh).unwrap();
    let back = io::read_shapes2(&path).unwrap();
    assert_eq!(back.polylines, sh.polylines);
    assert_eq!(back.polygons.len(), 2);
    for (a, b) in back.polygons.iter().zip(&sh.polygons) {
        for (k, (ra, rb)) in a.rings.iter().zip(&b.rings).enumerate() {
            let o = io::geojson::ring_orientation(ra);
            assert_eq!(o, if k == 0 { 1 } else { -1 });
            let mut sa = ra.iter().map(|q| (q.x, q.y)).collect::<Vec<_>>();
            let mut sb = rb.iter().map(|q| (q.x, q.y)).collect::<Vec<_>>();
            sa.sort_by(|x, y| x.partial_cmp(y).unwrap());
            sb.sort_by(|x, y| x.partial_cmp(y).unwrap());
            assert_eq!(sa, sb);
        }
    }
    // a closed polyline round-trips through GeoJSON
    let cl = Shapes2 {
        polygons: vec![],
        polylines: vec![Polyline {
            points: vec![p(0., 0.), p(1., 0.), p(1., 1.)],
            closed: true,
        }],
    };
    io::write_shapes2(&path, &cl).unwrap();
    assert_eq!(io::read_shapes2(&path).unwrap(), cl);
}

fn test_volume(dtype: DType) -> Volume {
    let dims = [5, 4, 3];
    let data: Vec<f32> = (0..60)
        .map(|i| match dtype {
            DType::U8 => (i * 4) as f32,
            DType::I16 => (i * 500 - 15000) as f32,
            DType::U16 => (i * 1000) as f32,
            DType::I32 => (i * 30_000_000 - 900_000_000) as f32,
            DType::F32 => (i as f32 - 30.0) * 0.1,
            DType::F64 => (i as f32).sqrt(),
        })
        .collect();
    Volume {
        dims,
        axes: Axes::Uniform {
            origin: [-1.5, 0.25, 1e-3],
            spacing: [0.5, 1.0, 2.5],
        },
        data,
        source_dtype: dtype,
        orientation: Default::default(),
    }
}

#[test]
fn volumes_round_trip_through_every_writer() {
    let dir = tempfile::tempdir().unwrap();
    for dt in [
        DType::U8,
        DType::I16,
        DType::U16,
        DType::I32,
        DType::F32,
        DType::F64,
    ] {
        let v = test_volume(dt);
        for name in ["v.nrrd", "v.mhd", "v.mha", "v.json"] {
            let path = dir.path().join(name);
            io::write_volume(&path, &v).unwrap();
            let mut back = io::read_volume(&path).unwrap();
            if name.starts_with("v.mh") {
                // MetaImage has no "unnamed" space: ITK reads every MHD in LPS
                assert_eq!(
                    back.orientation.space.as_deref(),
                    Some("left-posterior-superior"),
                    "{name} {dt:?}"
                );
                back.orientation.space = None;
            }
            assert_eq!(back, v, "{name} {dt:?}");
        }
        assert!(dir.path().join("v.raw").is_file());
    }
    // a non-integral value in an integer volume is written as f32 (lossless)
    let mut v = test_volume(DType::U8);
    v.data[3] = 0.5;
    let path = dir.path().join("w.nrrd");
    io::write_volume(&path, &v).unwrap();
    let back = io::read_volume(&path).unwrap();
    assert_eq!(back.data, v.data);
    assert_eq!(back.source_dtype, DType::F32);
}

/// Hand-written NRRD headers: detached raw and gzip, byte skip, line skip, big endian, text.
#[test]
fn nrrd_detached_and_attached_variants() {
    let dir = tempfile::tempdir().unwrap();
    let vals: Vec<i16> = (0..24).map(|i| i * 100 - 1000).collect();
    let le: Vec<u8> = vals.iter().flat_map(|v| v.to_le_bytes()).collect();
    let be: Vec<u8> = vals.iter().flat_map(|v| v.to_be_bytes()).collect();
    let expect: Vec<f32> = vals.iter().map(|&v| v as f32).collect();
    let hdr = |extra: &str| {
        format!(
            "NRRD0004\n# comment\ntype: short\ndimension: 3\nsizes: 2 3 4\n\
             space directions: (0.5,0,0) (0,2,0) (0,0,3)\nspace origin: (1,2,3)\nkey:=value\n{extra}"
        )
    };
    put(dir.path(), "d.raw", &le);
    put(dir.path(), "d.raw.gz", &gz(&le));
    let mut skipped = b"xxxxxxx".to_vec();
    skipped.extend_from_slice(&be);
    put(dir.path(), "s.raw", &skipped);
    let mut lines = b"line one\nline two\n".to_vec();
    lines.extend_from_slice(&le);
    put(dir.path(), "l.raw", &lines);
    let cases: Vec<(&str, Vec<u8>)> = vec![
        (
            "a.nhdr",
            hdr("endian: little\nencoding: raw\ndata file: d.raw\n").into_bytes(),
        ),
        (
            "b.nhdr",
            hdr("endian: little\nencoding: gzip\ndatafile: d.raw.gz\n").into_bytes(),
        ),
        (
            "c.nhdr",
            hdr("endian: big\nencoding: raw\nbyte skip: 7\ndata file: ./s.raw\n\n").into_bytes(),
        ),
        (
            "d.nhdr",
            hdr("endian: big\nencoding: raw\nbyte skip: -1\ndata file: s.raw\n").into_bytes(),
        ),
        (
            "e.nhdr",
            hdr("endian: little\nencoding: raw\nline skip: 2\ndata file: l.raw\n").into_bytes(),
        ),
        ("f.nrrd", {
            let mut b = hdr("endian: little\nencoding: raw\n\n").into_bytes();
            b.extend_from_slice(&le);
            b
        }),
        ("g.nrrd", {
            let mut b = hdr("endian: big\r\nencoding: gz\r\n\r\n").into_bytes();
            b.extend_from_slice(&gz(&be));
            b
        }),
        ("h.nrrd", {
            let mut b = hdr("encoding: ascii\n\n").into_bytes();
            for v in &vals {
                b.extend_from_slice(format!("{v}\n").as_bytes());
            }
            b
        }),
    ];
    for (name, bytes) in cases {
        let path = put(dir.path(), name, &bytes);
        let v = io::read_volume(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(v.dims, [2, 3, 4], "{name}");
        assert_eq!(v.data, expect, "{name}");
        assert_eq!(v.source_dtype, DType::I16);
        assert_eq!(
            v.axes,
            Axes::Uniform {
                origin: [1., 2., 3.],
                spacing: [0.5, 2., 3.]
            },
            "{name}"
        );
    }
    // 2D NRRD with spacings and uint8 synonyms; int8 and uint32 conversions
    let path = put(
        dir.path(),
        "two.nrrd",
        b"NRRD0005\ntype: unsigned char\ndimension: 2\nsizes: 3 2\nspacings: 2 nan\nencoding: raw\n\n\x00\x01\x02\x03\x04\xff",
    );
    let v = io::read_volume(&path).unwrap();
    assert_eq!(v.dims, [3, 2, 1]);
    assert_eq!(v.data, vec![0., 1., 2., 3., 4., 255.]);
    assert_eq!(v.spacing(), [2., 1., 1.]);
    let path = put(
        dir.path(),
        "i8.nrrd",
        b"NRRD0004\ntype: int8\ndimension: 3\nsizes: 2 1 1\nencoding: raw\n\n\xff\x7f",
    );
    let v = io::read_volume(&path).unwrap();
    assert_eq!(
        (v.data.clone(), v.source_dtype),
        (vec![-1., 127.], DType::I16)
    );
    let mut b =
        b"NRRD0004\ntype: uint32\ndimension: 3\nsizes: 1 1 1\nendian: big\nencoding: raw\n\n"
            .to_vec();
    b.extend_from_slice(&4_000_000_000u32.to_be_bytes());
    let v = io::read_volume(&put(dir.path(), "u32.nrrd", &b)).unwrap();
    assert_eq!((v.data[0], v.source_dtype), (4e9, DType::F64));
}

#[test]
fn metaimage_local_separate_and_zlib() {
    let dir = tempfile::tempdir().unwrap();
    let vals: Vec<f32> = (0..30).map(|i| i as f32 * 0.5 - 3.0).collect();
    let le: Vec<u8> = vals.iter().flat_map(|v| v.to_le_bytes()).collect();
    let be: Vec<u8> = vals.iter().flat_map(|v| v.to_be_bytes()).collect();
    let hdr = |extra: &str, file: &str| {
        format!(
            "ObjectType = Image\nNDims = 3\nDimSize = 5 3 2\nElementSpacing = 1 2 3\n\
             Offset = -1 -2 -3\nTransformMatrix = 1 0 0 0 1 0 0 0 1\nElementType = MET_FLOAT\n{extra}ElementDataFile = {file}\n"
        )
    };
    put(dir.path(), "data.raw", &le);
    put(dir.path(), "data.zraw", &zlib(&be));
    let mut hs = vec![9u8; 11];
    hs.extend_from_slice(&le);
    put(dir.path(), "hs.raw", &hs);
    let cases: Vec<(&str, Vec<u8>)> = vec![
        ("a.mhd", hdr("", "data.raw").into_bytes()),
        (
            "b.mhd",
            hdr(
                "ElementByteOrderMSB = True\nCompressedData = True\n",
                "data.zraw",
            )
            .into_bytes(),
        ),
        ("c.mhd", hdr("HeaderSize = 11\n", "hs.raw").into_bytes()),
        ("d.mhd", hdr("HeaderSize = -1\n", "hs.raw").into_bytes()),
        ("e.mha", {
            let mut b = hdr("BinaryDataByteOrderMSB = False\n", "LOCAL").into_bytes();
            b.extend_from_slice(&le);
            b
        }),
        ("f.mha", {
            let z = zlib(&be);
            let mut b = hdr(
                &format!(
                    "BinaryDataByteOrderMSB = True\nCompressedData = True\nCompressedDataSize = {}\n",
                    z.len()
                ),
                "LOCAL",
            )
            .into_bytes();
            b.extend_from_slice(&z);
            b
        }),
    ];
    for (name, bytes) in cases {
        let path = put(dir.path(), name, &bytes);
        let v = io::read_volume(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(v.dims, [5, 3, 2], "{name}");
        assert_eq!(v.data, vals, "{name}");
        assert_eq!(
            v.axes,
            Axes::Uniform {
                origin: [-1., -2., -3.],
                spacing: [1., 2., 3.]
            }
        );
    }
    // gzip is not zlib: a gzip stream declared as CompressedData is an error
    put(dir.path(), "gz.raw", &gz(&le));
    let path = put(
        dir.path(),
        "g.mhd",
        hdr("CompressedData = True\n", "gz.raw").as_bytes(),
    );
    assert!(io::read_volume(&path).is_err());
}

#[test]
fn sidecar_every_dtype_and_endianness() {
    let dir = tempfile::tempdir().unwrap();
    let dims = [3usize, 2, 2];
    for (dt, names) in [
        ("u8", &["u8", "uint8"][..]),
        ("i16", &["i16", "int16"]),
        ("u16", &["u16", "uint16"]),
        ("i32", &["i32", "int32"]),
        ("f32", &["f32", "float32"]),
        ("f64", &["f64", "float64"]),
    ] {
        let vals: Vec<f64> = (0..12)
            .map(|i| match dt {
                "u8" => (i * 20) as f64,
                "i16" => (i * 3000 - 20000) as f64,
                "u16" => (i * 5000) as f64,
                "i32" => (i * 100_000_000 - 600_000_000) as f64,
                _ => (i as f64 - 6.0) * 0.25,
            })
            .collect();
        for big in [false, true] {
            let bytes: Vec<u8> = vals
                .iter()
                .flat_map(|&v| -> Vec<u8> {
                    macro_rules! b {
                        ($x:expr) => {
                            if big {
                                $x.to_be_bytes().to_vec()
                            } else {
                                $x.to_le_bytes().to_vec()
                            }
                        };
                    }
                    match dt {
                        "u8" => vec![v as u8],
                        "i16" => b!(v as i16),
                        "u16" => b!(v as u16),
                        "i32" => b!(v as i32),
                        "f32" => b!(v as f32),
                        _ => b!(v),
                    }
                })
                .collect();
            for (k, name) in names.iter().enumerate() {
                let gzipped = k == 1;
                let raw = format!("{dt}_{big}_{k}.raw{}", if gzipped { ".gz" } else { "" });
                put(
                    dir.path(),
                    &raw,
                    &if gzipped { gz(&bytes) } else { bytes.clone() },
                );
                let json = if k == 0 {
                    format!(
                        r#"{{"data":"{raw}","dims":[3,2,2],"spacing":[1,2,3],"origin":[4,5,6],"dtype":"{name}","endian":"{}"}}"#,
                        if big { "big" } else { "little" }
                    )
                } else {
                    // the keys of the shipped sidecars
                    format!(
                        r#"{{"data_file":"{raw}","dims_xyz":[3,2,2],"spacing_xyz":[1,2,3],"origin":[4,5,6],"dtype":"{name}","endianness":"{}","header_bytes":0,"raw_bytes":{}}}"#,
                        if big { "big" } else { "little" },
                        bytes.len()
                    )
                };
                let path = put(dir.path(), &format!("{dt}_{big}_{k}.json"), json.as_bytes());
                let v = io::read_volume(&path).unwrap_or_else(|e| panic!("{json}: {e}"));
                assert_eq!(v.dims, dims);
                let expect: Vec<f32> = vals.iter().map(|&x| x as f32).collect();
                assert_eq!(v.data, expect, "{json}");
                assert_eq!(
                    v.axes,
                    Axes::Uniform {
                        origin: [4., 5., 6.],
                        spacing: [1., 2., 3.]
                    }
                );
            }
        }
    }
}

// ------------------------------------------------------------------------------------------
// real data

#[test]
fn real_volumes_load_identically_via_json_and_nhdr() {
    let Some(d) = data_dir() else { return };
    let cases = [
        (
            "cthead_8bit_256x256x99",
            [256, 256, 99],
            DType::U8,
            (0.0, 255.0),
        ),
        (
            "mni_icbm152_t1_2009a_197x233x189",
            [197, 233, 189],
            DType::U8,
            (0.0, 255.0),
        ),
        (
            "dipy_aniso_vox_58x58x24_i16",
            [58, 58, 24],
            DType::I16,
            (0.0, 2149.0),
        ),
    ];
    for (name, dims, dt, range) in cases {
        let a = io::read_volume(&d.join(format!("volumes/{name}.json"))).unwrap();
        let b = io::read_volume(&d.join(format!("volumes/{name}.nhdr"))).unwrap();
        assert_eq!(a.dims, dims, "{name}");
        assert_eq!(a.source_dtype, dt, "{name}");
        assert!(
            a.data == b.data,
            "{name}: data differ between .json and .nhdr"
        );
        if name.starts_with("dipy") {
            // the .nhdr carries spacing only; the sidecar also the oblique affine (its
            // translation, its directions)
            assert_eq!(a.spacing(), b.spacing(), "{name}");
            assert!(b.orientation.directions.is_none());
            assert!(a.orientation.directions.is_some(), "{name}: affine dropped");
        } else {
            assert_eq!(a.axes, b.axes, "{name}");
            assert_eq!(a.orientation, b.orientation, "{name}");
        }
        assert_eq!(a.value_range(), Some((range.0, range.1)), "{name}");
        let frac = |lo: f32, hi: f32| {
            a.data.iter().filter(|&&v| v >= lo && v <= hi).count() as f64 / a.data.len() as f64
        };
        match name {
            n if n.starts_with("cthead") => {
                // air dominates; soft tissue and bone present
                assert!(frac(0., 20.) > 0.3, "air {}", frac(0., 20.));
                assert!(frac(70., 100.) > 0.05);
                assert!(frac(140., 210.) > 0.01);
                assert_eq!(a.spacing(), [1., 1., 2.]);
            }
            n if n.starts_with("mni") => {
                assert!(frac(0., 0.) > 0.4, "background {}", frac(0., 0.));
                assert!(frac(24., 240.) > 0.1);
                assert_eq!(
                    a.axes,
                    Axes::Uniform {
                        origin: [-98., -134., -72.],
                        spacing: [1., 1., 1.]
                    }
                );
            }
            _ => {
                assert!(frac(150., 2149.) > 0.1);
                assert_eq!(a.spacing(), [4., 4., 5.]);
            }
        }
    }
}

#[test]
fn real_geostat_csv_columns() {
    let Some(d) = data_dir() else { return };
    let m = io::read_points(&d.join("geostat/meuse.csv")).unwrap();
    assert_eq!((m.dim, m.len()), (2, 155));
    let names: Vec<&str> = m.columns.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "cadmium", "copper", "lead", "zinc", "elev", "dist", "om", "ffreq", "soil", "lime",
            "dist.m"
        ]
    );
    assert_eq!(m.point(0), &[181072.0, 333611.0]);
    assert_eq!(m.column("zinc").unwrap().values[0], 1022.0);
    let om = &m.column("om").unwrap().values;
    assert_eq!(om.iter().filter(|v| v.is_nan()).count(), 2);
    for (f, rows) in [("jura_pred.csv", 259), ("jura_val.csv", 100)] {
        let j = io::read_points(&d.join("geostat").join(f)).unwrap();
        assert_eq!(j.len(), rows, "{f}");
        let names: Vec<&str> = j.columns.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(
            names,
            ["long", "lat", "Cd", "Co", "Cr", "Cu", "Ni", "Pb", "Zn"],
            "{f}"
        );
        assert!(
            j.coords.iter().all(|c| (0.0..10.0).contains(c)),
            "{f}: Xloc/Yloc are km"
        );
    }
}

#[test]
fn real_polygons_vertex_counts() {
    let Some(d) = data_dir() else { return };
    let pd = d.join("polygons");
    for (name, n) in [
        ("benelux_mainland_ne10m", 924),
        ("benelux_mainland_ne50m", 233),
        ("coast_great_britain_ne10m", 3697),
        ("coast_ireland_ne10m", 2245),
        ("coast_iceland_ne10m", 3058),
        ("coast_australia_mainland_ne10m", 9454),
    ] {
        for ext in ["csv", "geojson"] {
            let s = io::read_shapes2(&pd.join(format!("{name}.{ext}"))).unwrap();
            assert_eq!(s.polygons.len(), 1, "{name}.{ext}");
            assert_eq!(s.polygons[0].rings.len(), 1);
            assert_eq!(s.polygons[0].rings[0].len(), n, "{name}.{ext}");
            // README: all rings run clockwise
            assert_eq!(io::geojson::ring_orientation(&s.polygons[0].rings[0]), -1);
        }
        let a = io::read_shapes2(&pd.join(format!("{name}.csv"))).unwrap();
        let b = io::read_shapes2(&pd.join(format!("{name}.geojson"))).unwrap();
        assert_eq!(a, b, "{name}: CSV and GeoJSON differ");
        // as points too
        assert_eq!(
            io::read_points(&pd.join(format!("{name}.csv")))
                .unwrap()
                .len(),
            n
        );
    }
    let riv = io::read_shapes2(&pd.join("meuse_riv.csv")).unwrap();
    assert_eq!(riv.polygons[0].rings[0].len(), 175);
    let c = io::read_shapes2(&pd.join("benelux_countries_ne10m.geojson")).unwrap();
    assert_eq!(c.polygons.len(), 14);
    let lens: Vec<usize> = c.polygons[..2].iter().map(|p| p.rings[0].len()).collect();
    // the README's 196 and 644 count the closing repeat, which the reader drops
    assert_eq!(lens, [195, 643]);
    // README counts; five of the files do repeat the first vertex at the end (despite the
    // README), and the reader drops that closing repeat
    for (f, rings, outer) in [
        ("water.json", 10, 2396),
        ("water2.json", 8, 1005),
        ("dude.json", 3, 94),
        ("simplified-us-border.json", 2, 120),
        ("hilbert.json", 1, 1026),
        ("self-touching.json", 3, 116),
        ("building.json", 1, 15),
        ("collinear-diagonal.json", 1, 24),
        ("degenerate.json", 1, 6),
        ("hourglass.json", 1, 6),
    ] {
        let s = io::read_shapes2(&pd.join("mapbox_earcut").join(f)).unwrap();
        assert_eq!(s.polygons[0].rings.len(), rings, "{f}");
        assert_eq!(s.polygons[0].rings[0].len(), outer, "{f}");
    }
}

#[test]
fn real_curves2d_point_counts() {
    let Some(d) = data_dir() else { return };
    let cd = d.join("curves2d");
    for (f, n) in [
        ("ohrhallinger_hnncrust/crocodile-conf.p2d", 129),
        ("ohrhallinger_hnncrust/ventilator.p2d", 194),
        ("ohrhallinger_hnncrust/mushroom.p2d", 59),
        ("ohrhallinger_fitconnect/bot.txt", 1000),
        ("ohrhallinger_fitconnect/fish.txt", 1000),
        ("ohrhallinger_fitconnect/apple_2percent_noise.txt", 170),
        ("ohrhallinger_fitconnect/butterfly_2percent_noise.txt", 164),
        ("ohrhallinger_fitconnect/crab_2percent_noise.txt", 284),
        ("ohrhallinger_fitconnect/dolphin_2percent_noise.txt", 179),
        ("ohrhallinger_fitconnect/Cup0.txt", 263),
        ("ohrhallinger_fitconnect/Keyboard0.txt", 585),
        ("ohrhallinger_fitconnect/Monitor0.txt", 915),
        ("ohrhallinger_fitconnect/Mouse0.txt", 157),
    ] {
        let p = io::read_points(&cd.join(f)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((p.dim, p.len()), (2, n), "{f}");
    }
    // (file, points, components, closed components)
    for (f, n, comps, closed) in [
        ("Croco_samples.csv", 1221, 50, 0),
        ("Fishi_samples.csv", 734, 6, 0),
        ("Snail_samples.csv", 1135, 6, 3),
        ("blob2_samples.csv", 471, 1, 1),
        ("blob2_samples_sparse.csv", 118, 1, 1),
        ("simple_samples.csv", 437, 1, 1),
        ("simple_samples_sparse.csv", 109, 1, 1),
        ("spiral_samples.csv", 1477, 1, 1),
        ("spiral_samples_sparse.csv", 369, 1, 1),
        ("f1_samples.csv", 715, 7, 1),
        ("f2_samples.csv", 1095, 12, 3),
        ("f3_samples.csv", 732, 6, 0),
    ] {
        let path = cd.join("svg_groundtruth").join(f);
        let p = io::read_points(&path).unwrap();
        assert_eq!(p.len(), n, "{f}");
        let names: Vec<&str> = p.columns.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["component", "closed", "order"]);
        let s = io::read_shapes2(&path).unwrap();
        assert_eq!(s.polygons.len() + s.polylines.len(), comps, "{f}");
        assert_eq!(s.polygons.len(), closed, "{f}");
        let total: usize = s.polygons.iter().map(|p| p.rings[0].len()).sum::<usize>()
            + s.polylines.iter().map(|l| l.points.len()).sum::<usize>();
        assert_eq!(total, n, "{f}");
    }
}

// ------------------------------------------------------------------------------------------
// bad input

#[test]
fn empty_files_are_errors_everywhere() {
    let dir = tempfile::tempdir().unwrap();
    for name in [
        "e.csv",
        "e.xyz",
        "e.txt",
        "e.geojson",
        "e.nrrd",
        "e.nhdr",
        "e.mhd",
        "e.json",
    ] {
        let path = put(dir.path(), name, b"");
        assert!(io::read_points(&path).is_err(), "{name}");
        assert!(io::read_shapes2(&path).is_err(), "{name}");
        assert!(io::read_volume(&path).is_err(), "{name}");
    }
}

#[test]
fn huge_claimed_dims_fail_fast() {
    let dir = tempfile::tempdir().unwrap();
    put(dir.path(), "tiny.raw", &[0u8; 16]);
    put(dir.path(), "tiny.raw.gz", &gz(&[0u8; 16]));
    let files: Vec<(&str, String)> = vec![
        (
            "h1.nrrd",
            "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 100000 100000 100000\nencoding: raw\n\n\0\0"
                .into(),
        ),
        (
            "h2.nhdr",
            "NRRD0004\ntype: float\ndimension: 3\nsizes: 2000 2000 200\nencoding: gzip\ndata file: tiny.raw.gz\n".into(),
        ),
        (
            "h3.mhd",
            "NDims = 3\nDimSize = 100000 100000 100000\nElementType = MET_UCHAR\nElementDataFile = tiny.raw\n".into(),
        ),
        (
            "h4.json",
            r#"{"data":"tiny.raw","dims":[100000,100000,100000],"dtype":"u8"}"#.into(),
        ),
        (
            "h5.json",
            r#"{"data":"tiny.raw.gz","dims":[2000,2000,200],"dtype":"f64"}"#.into(),
        ),
        (
            "h6.nrrd",
            "NRRD0004\ntype: double\ndimension: 3\nsizes: 18446744073709551615 2 2\nencoding: raw\n\n".into(),
        ),
    ];
    for (name, text) in files {
        let path = put(dir.path(), name, text.as_bytes());
        let t = std::time::Instant::now();
        let e = err_of(io::read_volume(&path));
        assert!(
            t.elapsed().as_millis() < 500,
            "{name} took {:?}",
            t.elapsed()
        );
        assert!(!e.is_empty());
    }
}

#[test]
fn size_mismatches_truncation_and_bad_types() {
    let dir = tempfile::tempdir().unwrap();
    let le: Vec<u8> = (0..24u8).collect();
    put(dir.path(), "d.raw", &le);
    let g = gz(&le);
    put(dir.path(), "trunc.raw.gz", &g[..g.len() - 6]);
    put(dir.path(), "d.raw.gz", &g);
    let nh = |sizes: &str, ty: &str, enc: &str, file: &str| {
        format!("NRRD0004\ntype: {ty}\ndimension: 3\nsizes: {sizes}\nencoding: {enc}\ndata file: {file}\n")
    };
    let bad: Vec<(&str, String, &str)> = vec![
        ("m1.nhdr", nh("2 3 5", "uint8", "raw", "d.raw"), "bytes"),
        ("m2.nhdr", nh("2 3 3", "uint8", "raw", "d.raw"), "bytes"),
        ("m3.nhdr", nh("2 3 4", "uint8", "gzip", "trunc.raw.gz"), ""),
        ("m4.nhdr", nh("2 3 5", "uint8", "gzip", "d.raw.gz"), "bytes"),
        ("m5.nhdr", nh("2 3 4", "quaternion", "raw", "d.raw"), "type"),
        ("m6.nhdr", nh("2 3 4", "int64", "raw", "d.raw"), "64"),
        (
            "m7.nhdr",
            nh("2 3 4", "uint8", "bzip2", "d.raw"),
            "encoding",
        ),
        ("m8.nhdr", nh("2 3", "uint8", "raw", "d.raw"), "sizes"),
        (
            "m9.nhdr",
            nh("2 3 4", "uint8", "raw", "missing.raw"),
            "missing",
        ),
        ("m10.nhdr", "NRRD0004\ntype: uint8\n".into(), "dimension"),
        ("m11.nrrd", "NRRX0004\n".into(), "NRRD"),
        (
            "j1.json",
            r#"{"data":"d.raw","dims":[2,3,5],"dtype":"u8"}"#.into(),
            "bytes",
        ),
        (
            "j2.json",
            r#"{"data":"d.raw","dims":[2,3,4],"dtype":"complex64"}"#.into(),
            "type",
        ),
        (
            "j3.json",
            r#"{"data":"d.raw","dims":[2,3,4,1],"dtype":"u8"}"#.into(),
            "dims",
        ),
        ("j4.json", r#"{"dims":[2,3,4],"dtype":"u8"}"#.into(), "data"),
        (
            "j5.json",
            r#"{"data":"d.raw","dims":[2,3,4],"dtype":"u8","raw_bytes":25}"#.into(),
            "raw_bytes",
        ),
        (
            "j6.json",
            r#"{"data":"trunc.raw.gz","dims":[2,3,4],"dtype":"u8"}"#.into(),
            "",
        ),
        (
            "j7.json",
            r#"{"data":"d.raw","dims":[2,3,2],"dtype":"i16","endian":"middle"}"#.into(),
            "endian",
        ),
        (
            "j8.json",
            r#"{"data":"d.raw","dims":[2,3,4],"dtype":"u8","header_bytes":18446744073709551615,"raw_bytes":5}"#.into(),
            "",
        ),
        (
            "j9.json",
            r#"{"data":"d.raw.gz","dims":[2,3,4],"dtype":"u8","header_bytes":18446744073709551615}"#.into(),
            "",
        ),
        (
            "m12.nhdr",
            "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 3 4\nencoding: gzip\nbyte skip: 9223372036854775807\ndata file: d.raw.gz\n".into(),
            "",
        ),
        (
            "k4.mhd",
            "NDims = 3\nDimSize = 2 3 4\nElementType = MET_UCHAR\nHeaderSize = 9223372036854775807\nCompressedData = True\nElementDataFile = d.raw\n".into(),
            "HeaderSize",
        ),
        (
            "k5.mhd",
            "NDims = 3\nDimSize = 2 3 4\nElementType = MET_UCHAR\nHeaderSize = 9223372036854775807\nElementDataFile = d.raw\n".into(),
            "bytes",
        ),
        (
            "k1.mhd",
            "NDims = 3\nDimSize = 2 3 4\nElementType = MET_QUUX\nElementDataFile = d.raw\n".into(),
            "ElementType",
        ),
        (
            "k2.mhd",
            "NDims = 3\nDimSize = 2 3 4\nElementType = MET_SHORT\nElementDataFile = d.raw\n".into(),
            "bytes",
        ),
        (
            "k3.mhd",
            "NDims = 3\nDimSize = 2 3 4\nElementType = MET_UCHAR\n".into(),
            "ElementDataFile",
        ),
    ];
    for (name, text, needle) in bad {
        let path = put(dir.path(), name, text.as_bytes());
        let e = err_of(io::read_volume(&path));
        assert!(e.contains(needle), "{name}: {e}");
    }
}

#[test]
fn long_header_lines_are_refused_without_buffering() {
    let dir = tempfile::tempdir().unwrap();
    let mut long = b"NRRD0004\n# ".to_vec();
    long.extend(std::iter::repeat_n(b'a', 4 << 20));
    long.extend_from_slice(b"\ntype: uint8\n");
    let path = put(dir.path(), "long.nrrd", &long);
    let e = err_of(io::read_volume(&path));
    assert!(e.contains("line 2"), "{e}");
    let mut long = b"NDims = 3\nComment = ".to_vec();
    long.extend(std::iter::repeat_n(b'a', 4 << 20));
    let path = put(dir.path(), "long.mhd", &long);
    let e = err_of(io::read_volume(&path));
    assert!(e.contains("line 2"), "{e}");
}

#[test]
fn text_format_errors_name_lines() {
    let dir = tempfile::tempdir().unwrap();
    let cases: Vec<(&str, &[u8], &str)> = vec![
        ("n1.csv", b"x,y\n1,2\n3,NaN\n", "line 3"),
        ("n2.csv", b"x,y,z\n1,2,3\n4,5,inf\n", "line 3"),
        ("n3.csv", b"x,y\n1,2\n\xc3\x28,4\n", "line 3"),
        ("n4.xyz", b"1 2\n3 nan\n", "line 2"),
        ("n5.xyz", b"1 2\n\xff 4\n", "line 2"),
        ("n6.csv", b"x,y\n1,2,3\n", "line 2"),
    ];
    for (name, bytes, needle) in cases {
        let path = put(dir.path(), name, bytes);
        let e = err_of(io::read_points(&path));
        assert!(e.contains(needle), "{name}: {e}");
    }
    let path = put(
        dir.path(),
        "bad.geojson",
        b"{\"type\":\"Polygon\",\n\"coordinates\": [[[0,0],[1,\"a\"],[1,1]]]}",
    );
    assert!(io::read_shapes2(&path).is_err());
    let path = put(
        dir.path(),
        "bad2.geojson",
        b"{\"type\":\"Polygon\",\n\"coordinates\": [[[0,0],[1,",
    );
    let e = err_of(io::read_shapes2(&path));
    assert!(e.contains("line 2"), "{e}");
}

// ------------------------------------------------------------------------------------------
// fuzz-like property: truncations and mutations never panic

fn valid_samples() -> Vec<(&'static str, Vec<u8>)> {
    let mut nrrd_gz = b"NRRD0004\ntype: short\ndimension: 3\nsizes: 2 2 2\nendian: little\nencoding: gzip\nspace origin: (1,2,3)\nspacings: 1 1 1\n\n".to_vec();
    let vals: Vec<u8> = (0..16).collect();
    nrrd_gz.extend_from_slice(&gz(&vals));
    let mut nrrd_raw = b"NRRD0004\ntype: short\ndimension: 3\nsizes: 2 2 2\nendian: big\nencoding: raw\nbyte skip: -1\n\n".to_vec();
    nrrd_raw.extend_from_slice(&vals);
    let mut mha = b"ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementType = MET_SHORT\nCompressedData = True\nElementDataFile = LOCAL\n".to_vec();
    mha.extend_from_slice(&zlib(&vals));
    let mut mha_raw = b"NDims = 3\nDimSize = 2 2 2\nElementType = MET_USHORT\nHeaderSize = -1\nElementDataFile = LOCAL\n".to_vec();
    mha_raw.extend_from_slice(&vals);
    vec![
        ("f.csv", b"x,y,z,value,code\n1,2,3,4,A\n5,6,7,,B\n\"8\",9,10,11,C\n".to_vec()),
        ("g.csv", b"component,closed,ring,x,y\n0,1,0,0,0\n0,1,0,1,0\n0,1,0,1,1\n0,1,1,0.2,0.2\n0,1,1,0.4,0.2\n0,1,1,0.3,0.3\n1,0,0,5,5\n1,0,0,6,6\n".to_vec()),
        ("f.xyz", b"# x y z v\n1 2 3 4\n5 6 7 8\n".to_vec()),
        ("f.geojson", br#"{"type":"FeatureCollection","features":[{"type":"Feature","properties":{},"geometry":{"type":"MultiPolygon","coordinates":[[[[0,0],[1,0],[1,1],[0,0]],[[0.1,0.1],[0.2,0.1],[0.2,0.2],[0.1,0.1]]]]}},{"type":"Feature","geometry":{"type":"LineString","coordinates":[[0,0],[2,2]]}}]}"#.to_vec()),
        ("f.nrrd", nrrd_gz),
        ("r.nrrd", nrrd_raw),
        ("f.mha", mha),
        ("r.mha", mha_raw),
        ("f.json", br#"{"data":"side.raw","dims":[2,2,2],"dtype":"i16","endian":"big","spacing":[1,2,3]}"#.to_vec()),
    ]
}

fn read_all(path: &Path) {
    let _ = io::read_points(path);
    let _ = io::read_shapes2(path);
    let _ = io::read_volume(path);
    let _ = io::read_any(path);
}

#[test]
fn valid_samples_are_valid() {
    let dir = tempfile::tempdir().unwrap();
    put(dir.path(), "side.raw", &(0..16).collect::<Vec<u8>>());
    for (name, bytes) in valid_samples() {
        let path = put(dir.path(), name, &bytes);
        let ok = match name {
            "f.csv" | "f.xyz" => io::read_points(&path).map(|_| ()),
            "g.csv" | "f.geojson" => io::read_shapes2(&path).map(|_| ()),
            _ => io::read_volume(&path).map(|_| ()),
        };
        ok.unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

mod fuzz {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 192, .. ProptestConfig::default() })]
        #[test]
        fn truncations_and_mutations_never_panic(
            which in 0usize..9,
            cut in 0.0f64..1.0,
            edits in proptest::collection::vec((0.0f64..1.0, any::<u8>(), 0u8..3), 0..4),
            side_cut in 0usize..20,
        ) {
            let dir = tempfile::tempdir().unwrap();
            let side: Vec<u8> = (0..16).collect();
            put(dir.path(), "side.raw", &side[..side_cut.min(16)]);
            let (name, mut bytes) = valid_samples().swap_remove(which);
            for (pos, byte, kind) in edits {
                let i = ((bytes.len() as f64) * pos) as usize;
                match kind {
                    0 if i < bytes.len() => bytes[i] = byte,
                    1 => bytes.insert(i.min(bytes.len()), byte),
                    _ if i < bytes.len() => { bytes.remove(i); }
                    _ => {}
                }
            }
            let keep = ((bytes.len() as f64) * cut).ceil() as usize;
            bytes.truncate(keep.max(if cut > 0.5 { bytes.len() } else { 0 }));
            let path = put(dir.path(), name, &bytes);
            read_all(&path);
        }
    }
}

mod fuzz_bytes {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 256, .. ProptestConfig::default() })]
        /// Random text from a CSV/XYZ/GeoJSON-ish alphabet never panics the byte parsers.
        #[test]
        fn random_text_never_panics(
            s in "[xyzXYZ,;\\t \"\\n\\r0-9.eE+naNA#\\[\\]{}:-]{0,200}",
        ) {
            let b = s.as_bytes();
            let _ = io::csv::read_points(b);
            let _ = io::csv::read_polygon(b);
            let _ = io::xyz::read(b);
            let _ = io::geojson::read(b);
        }

        /// Valid CSV points survive a write/read round trip exactly.
        #[test]
        fn csv_points_round_trip(
            pts in proptest::collection::vec((-1e12f64..1e12, -1e-3f64..1e-3, any::<f64>()), 1..20),
        ) {
            let ps = PointSet {
                dim: 2,
                coords: pts.iter().flat_map(|p| [p.0, p.1]).collect(),
                columns: vec![Column { name: "v".into(), values: pts.iter().map(|p| p.2).collect() }],
            };
            let mut out = Vec::new();
            io::csv::write_points(&mut out, &ps).unwrap();
            let back = io::csv::read_points(&out).unwrap();
            prop_assert_eq!(&back.coords, &ps.coords);
            for (a, b) in back.columns[0].values.iter().zip(&ps.columns[0].values) {
                prop_assert!(a == b || (a.is_nan() && b.is_nan()));
            }
        }
    }
}

#[test]
fn non_uniform_axes_are_not_written_and_leave_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let v = Volume {
        dims: [2, 2, 1],
        axes: Axes::Coords([vec![0.0, 1.0], vec![0.0, 3.0], vec![0.0]]),
        data: vec![1.0; 4],
        source_dtype: DType::F32,
        orientation: Default::default(),
    };
    for name in ["c.nrrd", "c.mhd", "c.json"] {
        let path = dir.path().join(name);
        assert!(io::write_volume(&path, &v).is_err(), "{name}");
        assert!(!path.exists(), "{name}");
    }
    let leftovers: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

/// An output named `*.gz` is gzip-compressed (it was plain text under a `.gz` name, which no
/// gzip tool reads), reads back identically, and volumes refuse `.gz` without writing anything.
#[test]
fn gz_outputs_are_compressed() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = morpho::mesh::TriMesh::new(
        vec![
            morpho::geom::Point3::new(0.0, 0.0, 0.0),
            morpho::geom::Point3::new(1.0, 0.0, 0.0),
            morpho::geom::Point3::new(0.0, 1.0, 0.0),
            morpho::geom::Point3::new(0.0, 0.0, 1.0),
        ],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    );
    for name in ["m.ply.gz", "m.OBJ.GZ", "m.off.gz", "m.stl.gz"] {
        let p = dir.path().join(name);
        io::write_mesh(&p, &mesh, io::Encoding::default()).unwrap();
        let bytes = std::fs::read(&p).unwrap();
        assert_eq!(&bytes[..2], &[0x1f, 0x8b], "{name}: not gzip");
        let back = io::read_mesh(&p).unwrap();
        if name.ends_with("stl.gz") {
            // STL stores triangle corners; reading welds them in order of appearance
            assert_eq!(back.triangles.len(), 4);
            assert_eq!(back.signed_volume(), mesh.signed_volume());
        } else {
            assert_eq!(back.triangles, mesh.triangles, "{name}");
            assert_eq!(back.positions, mesh.positions, "{name}");
        }
    }
    let v = test_volume(DType::U8);
    for name in ["v.nrrd.gz", "v.mhd.gz", "v.json.gz"] {
        let p = dir.path().join(name);
        let e = io::write_volume(&p, &v).unwrap_err().to_string();
        assert!(e.contains("not written as .gz"), "{e}");
    }
    let mut left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    left.sort();
    assert_eq!(left, ["m.OBJ.GZ", "m.off.gz", "m.ply.gz", "m.stl.gz"]);
}
