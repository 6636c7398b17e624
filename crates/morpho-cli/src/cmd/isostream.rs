//! `morpho isosurface VOLUME --level A -o MESH.ply --stream`: the contour surface of a volume
//! larger than memory (issue 24). Two passes over the file: the first finds the range of the
//! finite samples (ε of H Rem. 3.8 depends on it, as in memory), the second reads slabs of
//! z-slices (`--slab-mib` of samples, with the one-slice halo the gradients need), extracts
//! each slab's cells on all cores (sub-slabs along z, `morpho::volume::isosurface_block`),
//! and hands them in order to `morpho::volume::IsoStream`, which emits vertices and triangles
//! in their final order; they are spooled into temporary files beside the output
//! (`morpho::io::ply::MeshSpool`) and the PLY is written at the end, byte for byte the file
//! the in-memory path writes (tests/cli_stream.rs).
//!
//! Memory: one slab of samples (`--slab-mib`, default 64 MiB, plus its halo) and the two
//! copies the extraction makes of it (`isosurface_block` builds a volume of the block and one
//! of its cells), the extraction output of one slab twice (the stream holds the previous one),
//! and 4 bytes per output triangle for the parts (union–find); disk: about twice the output.
//! Measured (bench/stream_scale.py): 1024³ float32 (4 GiB) → 20.3M triangles in 1.28 GB peak
//! RSS with 256 MiB slabs, under a 2 GiB address-space limit. `--largest-part` needs the whole
//! mesh and is refused.

use super::isosurface::{finite_extent, options, report_figures, Args};
use crate::report::Report;
use crate::Failure;
use morpho::io::{self, ply::MeshSpool, Encoding};
use morpho::volume::{
    finite_range, isosurface_block, IsoBlock, IsoStream, NormalMethod, StreamPiece,
};
use rayon::prelude::*;
use std::time::Instant;

pub fn run(args: &Args, report: &mut Report) -> Result<u8, Failure> {
    if io::Format::of(&args.output)? != io::Format::Ply {
        return Err(Failure::usage(
            "--stream writes PLY only (the output's counts are known at the end)",
        ));
    }
    if args.largest_part {
        return Err(Failure::usage(
            "--largest-part needs the whole mesh in memory; it cannot be used with --stream",
        ));
    }
    let t0 = Instant::now();
    // pass 1: the range of the finite samples
    let mut s = io::open_volume_stream(&args.input)?;
    let grid = s.grid();
    let d = grid.dims;
    finite_extent(&grid.axes, d, &args.input)?;
    let plane = d[0] * d[1];
    if !(args.slab_mib > 0.0 && args.slab_mib.is_finite()) {
        return Err(Failure::usage("--slab-mib must be a positive number"));
    }
    // slices per slab (f64 → usize saturates)
    let slab = ((args.slab_mib * (1u64 << 20) as f64) / (4 * plane).max(1) as f64) as usize;
    let slab = slab.clamp(1, d[2].max(1));
    let mut buf: Vec<f32> = Vec::new();
    let mut range: Option<(f32, f32)> = None;
    while s.slices_left() > 0 {
        buf.clear();
        s.read_slices(slab, &mut buf)?;
        range = finite_range(&buf, range);
    }
    s.finish()?;
    if d.iter().any(|&k| k < 2) {
        range = None;
    }
    report.add_time("range", t0.elapsed().as_secs_f64());
    // pass 2: slabs of cells z0..z1 with samples z0−1..z1+2
    let t1 = Instant::now();
    let opts = options(args);
    let mut stream = IsoStream::new(grid.clone(), range, &opts)?;
    let dir = match args.output.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    };
    let enc = if args.ascii {
        Encoding::Ascii
    } else {
        Encoding::BinaryLittleEndian
    };
    let normals = opts.normals != NormalMethod::None;
    let mut spool = MeshSpool::new(&dir, enc, normals)?;
    let mut piece = StreamPiece::default();
    let cells = d[2].saturating_sub(1);
    if !stream.is_empty() {
        let mut s = io::open_volume_stream(&args.input)?;
        // buf holds samples of slices lo..lo + buf.len() / plane
        let mut lo = 0usize;
        buf.clear();
        let threads = if opts.parallel {
            rayon::current_num_threads()
        } else {
            1
        };
        let mut z0 = 0;
        while z0 < cells {
            let z1 = (z0 + slab).min(cells);
            let (s0, s1) = (z0.saturating_sub(1), (z1 + 2).min(d[2]));
            // drop slices below s0, read up to s1
            let drop = (s0 - lo) * plane;
            buf.drain(..drop.min(buf.len()));
            lo = s0;
            let have = lo + buf.len() / plane;
            if s1 > have {
                s.read_slices(s1 - have, &mut buf)?;
            }
            // sub-slabs of the slab's cells, one per thread
            let per = (z1 - z0).div_ceil(threads).max(1);
            let subs: Vec<[usize; 2]> = (z0..z1)
                .step_by(per)
                .map(|a| [a, (a + per).min(z1)])
                .collect();
            let extract = |&[a, b]: &[usize; 2]| {
                let (t0, t1) = (a.saturating_sub(1), (b + 2).min(d[2]));
                let samples = &buf[(t0 - lo) * plane..(t1 - lo) * plane];
                isosurface_block(
                    &grid,
                    samples,
                    [d[0], d[1], t1 - t0],
                    [0, 0, t0],
                    [[0, d[0] - 1], [0, d[1] - 1], [a, b]],
                    range,
                    &opts,
                )
            };
            let blocks: Vec<Result<IsoBlock, _>> = if threads > 1 {
                subs.par_iter().map(extract).collect()
            } else {
                subs.iter().map(extract).collect()
            };
            for (b, z) in blocks.into_iter().zip(&subs) {
                stream.push(b?, *z, &mut piece)?;
                drain(&mut spool, &mut piece)?;
            }
            z0 = z1;
        }
        s.finish()?;
    }
    let sum = stream.finish(&mut piece)?;
    drain(&mut spool, &mut piece)?;
    report.add_time("compute", t1.elapsed().as_secs_f64());
    let t2 = Instant::now();
    let part = |t: usize| sum.part(t).unwrap_or(0);
    let part_fn: Option<&dyn Fn(usize) -> u32> =
        (opts.topology && sum.triangles > 0).then_some(&part as &dyn Fn(usize) -> u32);
    spool.finish(&args.output, |c| sum.resolve(c), part_fn)?;
    report.add_time("write", t2.elapsed().as_secs_f64());
    report_figures(report, args, &sum.figures);
    report.set("stream", true);
    report.set("slab_slices", slab);
    report.set("vertices", sum.edge_vertices + sum.interior_vertices);
    report.set("triangles", sum.triangles);
    report.set("input", args.input.display().to_string());
    report.set("output", args.output.display().to_string());
    Ok(0)
}

/// Moves what the stream emitted into the spool.
fn drain(spool: &mut MeshSpool, p: &mut StreamPiece) -> Result<(), Failure> {
    spool.vertices(&p.positions, &p.normals)?;
    spool.late_vertices(&p.interior_positions, &p.interior_normals)?;
    spool.triangles(&p.triangles)?;
    p.clear();
    Ok(())
}
