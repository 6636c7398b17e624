//! GeoJSON (RFC 7946) polygons and line strings, and the earcut fixture format.
//!
//! # Reading
//! `Polygon`, `MultiPolygon`, `LineString`, `MultiLineString`, alone or inside `Feature`,
//! `FeatureCollection` and `GeometryCollection` (any nesting serde_json accepts, ≤ 128 levels).
//! `Point`/`MultiPoint` and null geometries are skipped here (points are read by [`read_points`]);
//! properties are ignored. Positions
//! need at least 2 numbers (further numbers, e.g. z, are ignored). A ring's closing repeat is
//! dropped; a ring needs at least 3 vertices after that. A `LineString` whose last position
//! repeats its first (and that has ≥ 4 positions) becomes a closed [`Polyline`] without the
//! repeat. Orientation is kept as in the file. A top-level JSON array of rings of `[x, y]`
//! (mapbox/earcut fixtures: ring 0 outer, others holes) is read as one polygon.
//!
//! # Writing
//! A `FeatureCollection` with one `Feature` per shape (`properties: {}`): polygons as `Polygon`
//! with explicitly closed rings, the outer ring counter-clockwise and holes clockwise
//! (RFC 7946 §3.1.6) — a ring is reversed when the sign of its signed area, computed
//! **exactly** ([`ring_orientation`]), disagrees; polylines as `LineString` (closed ones with
//! the first position repeated at the end). Numbers use serde_json's shortest round-trip form.
//!
//! Results: [`write_boundary_2d`] (one `Polygon` feature, the boundary in its own
//! counter-clockwise order, properties `all_on_boundary` and `indices`) and [`write_contour`]
//! (one `Polygon` per region of a plane contour — outer rings counter-clockwise, holes clockwise
//! as the contour gives them — with properties `threshold`, `value`, `below`, `area`,
//! `external`).
//!
//! **Coordinate reference system.** RFC 7946 coordinates are WGS84 longitude/latitude, and
//! readers assume so. morpho never writes a `crs` member unless told or carrying an input's
//! (see [`carry_input_crs`]): [`set_crs`] (the CLI's
//! global `--crs`, e.g. `--crs EPSG:28992` for the Meuse data in RD New metres) adds the
//! 2008-spec member `"crs": {"type": "name", "properties": {"name":
//! "urn:ogc:def:crs:EPSG::28992"}}` (an `EPSG:n` code is written as its OGC URN, any other
//! name as given) to every FeatureCollection written afterwards, which GDAL/OGR, QGIS and
//! geopandas honour.
//!
//! Complexity: linear in the input size.

use crate::boundary::Boundary2;
use crate::contour::PlaneContour;
use crate::geom::expansion::grow;
use crate::geom::Point2;
use crate::mesh::{Column, PointSet, Polygon, Polyline, Shapes2};
use crate::{Error, Result};
use serde_json::{json, Value};
use std::io::Write;
use std::sync::Mutex;

fn position(v: &Value, ctx: &str) -> Result<Point2> {
    let a = v
        .as_array()
        .ok_or_else(|| Error::format(format!("{ctx}: a position must be an array of numbers")))?;
    if a.len() < 2 {
        return Err(Error::format(format!(
            "{ctx}: a position needs at least 2 numbers"
        )));
    }
    let num = |x: &Value| {
        x.as_f64()
            .filter(|f| f.is_finite())
            .ok_or_else(|| Error::format(format!("{ctx}: a coordinate is not a finite number")))
    };
    Ok(Point2::new(num(&a[0])?, num(&a[1])?))
}

fn positions(v: &Value, ctx: &str) -> Result<Vec<Point2>> {
    v.as_array()
        .ok_or_else(|| Error::format(format!("{ctx}: expected an array of positions")))?
        .iter()
        .map(|p| position(p, ctx))
        .collect()
}

fn ring(v: &Value, ctx: &str) -> Result<Vec<Point2>> {
    let mut r = positions(v, ctx)?;
    if r.len() > 1 && r.first() == r.last() {
        r.pop();
    }
    if r.len() < 3 {
        return Err(Error::format(format!(
            "{ctx}: a polygon ring needs at least 3 distinct positions"
        )));
    }
    Ok(r)
}

fn polygon(v: &Value, ctx: &str) -> Result<Option<Polygon>> {
    let rings = v
        .as_array()
        .ok_or_else(|| Error::format(format!("{ctx}: expected an array of rings")))?;
    if rings.is_empty() {
        return Ok(None);
    }
    Ok(Some(Polygon {
        rings: rings.iter().map(|r| ring(r, ctx)).collect::<Result<_>>()?,
    }))
}

fn line_string(v: &Value, ctx: &str) -> Result<Option<Polyline>> {
    let mut pts = positions(v, ctx)?;
    if pts.is_empty() {
        return Ok(None);
    }
    if pts.len() < 2 {
        return Err(Error::format(format!(
            "{ctx}: a LineString needs at least 2 positions"
        )));
    }
    let closed = pts.len() >= 4 && pts.first() == pts.last();
    if closed {
        pts.pop();
    }
    Ok(Some(Polyline {
        points: pts,
        closed,
    }))
}

fn coords<'a>(o: &'a Value, ty: &str) -> Result<&'a Value> {
    o.get("coordinates")
        .ok_or_else(|| Error::format(format!("{ty} without \"coordinates\"")))
}

fn walk(v: &Value, out: &mut Shapes2) -> Result<()> {
    let ty = v
        .get("type")
        .and_then(Value::as_str)
        .ok_or_else(|| Error::format("a GeoJSON object needs a \"type\" string"))?;
    match ty {
        "FeatureCollection" => {
            let fs = v
                .get("features")
                .and_then(Value::as_array)
                .ok_or_else(|| Error::format("FeatureCollection without a \"features\" array"))?;
            for f in fs {
                walk(f, out)?;
            }
        }
        "Feature" => match v.get("geometry") {
            None | Some(Value::Null) => {}
            Some(g) => walk(g, out)?,
        },
        "GeometryCollection" => {
            let gs = v
                .get("geometries")
                .and_then(Value::as_array)
                .ok_or_else(|| {
                    Error::format("GeometryCollection without a \"geometries\" array")
                })?;
            for g in gs {
                walk(g, out)?;
            }
        }
        "Polygon" => out.polygons.extend(polygon(coords(v, ty)?, ty)?),
        "MultiPolygon" => {
            let ps = coords(v, ty)?
                .as_array()
                .ok_or_else(|| Error::format("MultiPolygon: expected an array of polygons"))?;
            for p in ps {
                out.polygons.extend(polygon(p, ty)?);
            }
        }
        "LineString" => out.polylines.extend(line_string(coords(v, ty)?, ty)?),
        "MultiLineString" => {
            let ls = coords(v, ty)?
                .as_array()
                .ok_or_else(|| Error::format("MultiLineString: expected an array of lines"))?;
            for l in ls {
                out.polylines.extend(line_string(l, ty)?);
            }
        }
        "Point" | "MultiPoint" => {}
        other => {
            return Err(Error::unsupported(format!(
                "unknown GeoJSON type \"{other}\""
            )))
        }
    }
    Ok(())
}

/// Reads all polygons and line strings.
pub fn read(bytes: &[u8]) -> Result<Shapes2> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let v: Value = serde_json::from_slice(bytes)
        .map_err(|e| Error::at_line(e.line() as u64, format!("bad JSON: {e}")))?;
    let mut out = Shapes2::default();
    if v.is_array() {
        // earcut fixture: [[ [x, y], … ], …]
        out.polygons.extend(polygon(&v, "array of rings")?);
    } else {
        walk(&v, &mut out)?;
        note_input_crs(&v);
    }
    Ok(out)
}

/// Sign of the signed area of a ring (positive = counter-clockwise), computed exactly: the
/// shoelace sum Σ (xᵢ·yᵢ₊₁ − xᵢ₊₁·yᵢ) is accumulated as an exact floating-point expansion
/// (products split with fused multiply-add). If an intermediate overflows, the sign of
/// `orient2d` at the lexicographically lowest vertex is used (exact for simple rings).
/// Returns 0 for a ring of zero area.
pub fn ring_orientation(ring: &[Point2]) -> i32 {
    let n = ring.len();
    if n < 3 {
        return 0;
    }
    let mut e: Vec<f64> = Vec::new();
    let mut finite = true;
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        for (p, sign) in [(a.x * b.y, 1.0), (b.x * a.y, -1.0)] {
            let (u, v) = if sign > 0.0 { (a.x, b.y) } else { (b.x, a.y) };
            let err = u.mul_add(v, -p);
            if !p.is_finite() || !err.is_finite() {
                finite = false;
            }
            grow(&mut e, sign * p);
            grow(&mut e, sign * err);
        }
        if !finite {
            break;
        }
        if e.len() > 64 {
            // cannot happen for nonoverlapping doubles (≤ ~40 components), but stay bounded
            finite = false;
            break;
        }
    }
    if finite && e.iter().all(|v| v.is_finite()) {
        return match e.last() {
            Some(&v) if v > 0.0 => 1,
            Some(&v) if v < 0.0 => -1,
            _ => 0,
        };
    }
    // fallback: orientation at the extreme vertex
    let mut m = 0;
    for i in 1..n {
        if (ring[i].x, ring[i].y) < (ring[m].x, ring[m].y) {
            m = i;
        }
    }
    let prev = (1..n)
        .map(|k| ring[(m + n - k) % n])
        .find(|p| *p != ring[m]);
    let next = (1..n).map(|k| ring[(m + k) % n]).find(|p| *p != ring[m]);
    match (prev, next) {
        (Some(p), Some(q)) => {
            let o = crate::geom::orient2d(&p, &ring[m], &q);
            if o > 0.0 {
                1
            } else if o < 0.0 {
                -1
            } else {
                0
            }
        }
        _ => 0,
    }
}

fn closed_ring(r: &[Point2], ccw: bool) -> Result<Value> {
    let o = ring_orientation(r);
    let flip = (ccw && o < 0) || (!ccw && o > 0);
    let mut pts: Vec<Value> = Vec::with_capacity(r.len() + 1);
    let mut push = |p: &Point2| -> Result<()> {
        if !(p.x.is_finite() && p.y.is_finite()) {
            return Err(Error::invalid("cannot write a non-finite coordinate"));
        }
        pts.push(json!([p.x, p.y]));
        Ok(())
    };
    if flip {
        for p in r.iter().rev() {
            push(p)?;
        }
        if let Some(p) = r.last() {
            push(p)?;
        }
    } else {
        for p in r {
            push(p)?;
        }
        if let Some(p) = r.first() {
            push(p)?;
        }
    }
    Ok(Value::Array(pts))
}

static CRS: Mutex<Option<String>> = Mutex::new(None);
/// The first named `crs` read from an input since [`carry_input_crs`] was turned on.
static INPUT_CRS: Mutex<Option<String>> = Mutex::new(None);
static CARRY: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Turns on (or off) carrying an input's `crs`: once on, the first GeoJSON read whose top
/// level names a `crs` (`{"type":"name","properties":{"name":…}}`) has that name written into
/// every GeoJSON output that [`set_crs`] did not name — so a file in RD New stays RD New.
/// Off by default (a library reading unrelated files must not tag one with another's CRS);
/// the CLI turns it on for each run.
pub fn carry_input_crs(on: bool) {
    CARRY.store(on, std::sync::atomic::Ordering::Relaxed);
    *INPUT_CRS.lock().unwrap_or_else(|e| e.into_inner()) = None;
}

fn note_input_crs(doc: &Value) {
    if !CARRY.load(std::sync::atomic::Ordering::Relaxed) {
        return;
    }
    let Some(name) = doc
        .pointer("/crs/properties/name")
        .and_then(Value::as_str)
        .filter(|n| !n.is_empty() && !n.chars().any(char::is_control))
    else {
        return;
    };
    let mut slot = INPUT_CRS.lock().unwrap_or_else(|e| e.into_inner());
    if slot.is_none() {
        *slot = Some(name.to_string());
    }
}

/// Sets (or, with `None`, clears) the coordinate reference system named in every GeoJSON
/// written afterwards in this process (see the module documentation). `EPSG:n` (any case)
/// becomes `urn:ogc:def:crs:EPSG::n`; other names are written as given. Refused: an empty name
/// or one with control characters.
pub fn set_crs(name: Option<&str>) -> Result<()> {
    let value = match name.map(str::trim) {
        None => None,
        Some(n) if n.is_empty() || n.chars().any(char::is_control) => {
            return Err(Error::invalid(format!(
                "--crs needs a name such as EPSG:28992, not '{}'",
                n.escape_debug()
            )));
        }
        Some(n) => Some(match n.split_once(':') {
            Some((auth, code))
                if auth.eq_ignore_ascii_case("epsg")
                    && !code.is_empty()
                    && code.chars().all(|c| c.is_ascii_digit()) =>
            {
                format!("urn:ogc:def:crs:EPSG::{code}")
            }
            _ => n.to_string(),
        }),
    };
    *CRS.lock().unwrap_or_else(|e| e.into_inner()) = value;
    Ok(())
}

/// `doc` with the `crs` member when one is set (or carried from an input).
fn with_crs(mut doc: Value) -> Value {
    let set = CRS.lock().unwrap_or_else(|e| e.into_inner()).clone();
    let name = set.or_else(|| INPUT_CRS.lock().unwrap_or_else(|e| e.into_inner()).clone());
    if let Some(name) = name {
        doc["crs"] = json!({"type": "name", "properties": {"name": name}});
    }
    doc
}

/// Writes a FeatureCollection.
pub fn write(w: &mut dyn Write, shapes: &Shapes2) -> Result<()> {
    let mut features = Vec::new();
    for poly in &shapes.polygons {
        let rings = poly
            .rings
            .iter()
            .enumerate()
            .map(|(i, r)| closed_ring(r, i == 0))
            .collect::<Result<Vec<_>>>()?;
        features.push(json!({
            "type": "Feature",
            "properties": {},
            "geometry": {"type": "Polygon", "coordinates": rings},
        }));
    }
    for line in &shapes.polylines {
        let mut pts = Vec::with_capacity(line.points.len() + 1);
        for p in &line.points {
            if !(p.x.is_finite() && p.y.is_finite()) {
                return Err(Error::invalid("cannot write a non-finite coordinate"));
            }
            pts.push(json!([p.x, p.y]));
        }
        if line.closed {
            if let Some(p) = line.points.first() {
                pts.push(json!([p.x, p.y]));
            }
        }
        features.push(json!({
            "type": "Feature",
            "properties": {},
            "geometry": {"type": "LineString", "coordinates": pts},
        }));
    }
    let doc = json!({"type": "FeatureCollection", "features": features});
    super::json::write_value(w, &with_crs(doc))
}

/// Writes a 2D boundary polygon (input indices into `points`, counter-clockwise) as a
/// FeatureCollection of one `Polygon` feature with the properties `all_on_boundary` and
/// `indices` (the polygon's input indices).
///
/// ```
/// use morpho::boundary::{boundary_2d, Options2};
/// use morpho::geom::Point2;
/// let p = [Point2::new(0.0, 0.0), Point2::new(2.0, 0.0), Point2::new(2.0, 2.0), Point2::new(0.0, 2.0)];
/// let b = boundary_2d(&p, &Options2::default()).unwrap();
/// let mut out = Vec::new();
/// morpho::io::geojson::write_boundary_2d(&mut out, &p, &b).unwrap();
/// let back = morpho::io::geojson::read(&out).unwrap();
/// assert_eq!(back.polygons[0].rings[0].len(), 4);
/// ```
pub fn write_boundary_2d(w: &mut dyn Write, points: &[Point2], b: &Boundary2) -> Result<()> {
    let mut ring: Vec<[f64; 2]> = b
        .polygon
        .iter()
        .map(|&i| [points[i as usize].x, points[i as usize].y])
        .collect();
    if let Some(&f) = ring.first() {
        ring.push(f);
    }
    let v = json!({
        "type": "FeatureCollection",
        "features": [{
            "type": "Feature",
            "properties": { "all_on_boundary": b.all_on_boundary, "indices": b.polygon },
            "geometry": { "type": "Polygon", "coordinates": [ring] }
        }]
    });
    super::json::write_value(w, &with_crs(v))
}

/// A closed ring of vertex indices into `points` as GeoJSON positions.
fn index_ring(ring: &[u32], points: &[Point2]) -> Value {
    let mut v: Vec<Value> = ring
        .iter()
        .map(|&i| json!([points[i as usize].x, points[i as usize].y]))
        .collect();
    if let Some(first) = v.first().cloned() {
        v.push(first);
    }
    Value::Array(v)
}

/// The GeoJSON FeatureCollection of a plane contour's regions (see the module documentation);
/// `threshold` and `below` are the parameters that made the contour.
pub fn contour_value(r: &PlaneContour, threshold: f64, below: bool) -> Value {
    let c = &r.contour;
    let features: Vec<Value> = c
        .regions
        .iter()
        .map(|reg| {
            let rings: Vec<Value> = std::iter::once(reg.outer)
                .chain(reg.holes.iter().copied())
                .map(|k| index_ring(&c.cycles[k as usize], &r.points))
                .collect();
            json!({
                "type": "Feature",
                "geometry": {"type": "Polygon", "coordinates": rings},
                "properties": {
                    "threshold": threshold,
                    "value": r.selected.column,
                    "below": below,
                    "area": reg.area,
                    "external": reg.external,
                }
            })
        })
        .collect();
    json!({"type": "FeatureCollection", "features": features})
}

/// Writes [`contour_value`].
pub fn write_contour(
    w: &mut dyn Write,
    r: &PlaneContour,
    threshold: f64,
    below: bool,
) -> Result<()> {
    super::json::write_value(w, &with_crs(contour_value(r, threshold, below)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::orient2d;

    fn p(x: f64, y: f64) -> Point2 {
        Point2::new(x, y)
    }

    #[test]
    fn orientation_is_exact_on_tiny_and_offset_rings() {
        let sq = [p(0., 0.), p(1., 0.), p(1., 1.), p(0., 1.)];
        assert_eq!(ring_orientation(&sq), 1);
        let rev: Vec<_> = sq.iter().rev().copied().collect();
        assert_eq!(ring_orientation(&rev), -1);
        // a sliver far from the origin: float shoelace cancels, the exact sum does not
        let big = 1e15;
        let t = [
            p(big, big),
            p(big + 1.0, big),
            p(big + 2.0, big + 2f64.powi(-2)),
        ];
        let o = orient2d(&t[0], &t[1], &t[2]);
        assert_eq!(ring_orientation(&t), o.signum() as i32);
        let flat = [p(0., 0.), p(1., 1.), p(2., 2.)];
        assert_eq!(ring_orientation(&flat), 0);
    }

    #[test]
    fn reads_nested_collections() {
        let s = br#"{"type":"FeatureCollection","features":[
          {"type":"Feature","properties":{"a":1},"geometry":{"type":"GeometryCollection","geometries":[
            {"type":"Polygon","coordinates":[[[0,0,5],[1,0,5],[1,1,5],[0,0,5]]]},
            {"type":"MultiLineString","coordinates":[[[0,0],[1,1]],[[0,0],[1,0],[1,1],[0,0]]]}]}},
          {"type":"Feature","geometry":null},
          {"type":"Feature","geometry":{"type":"Point","coordinates":[1,2]}}]}"#;
        let sh = read(s).unwrap();
        assert_eq!(sh.polygons.len(), 1);
        assert_eq!(sh.polygons[0].rings[0].len(), 3);
        assert_eq!(sh.polylines.len(), 2);
        assert!(!sh.polylines[0].closed);
        assert!(sh.polylines[1].closed);
        assert_eq!(sh.polylines[1].points.len(), 3);
        assert!(read(br#"{"type":"Polygon","coordinates":[[[0,0],[1,0]]]}"#).is_err());
        assert!(read(br#"{"type":"Polygon"}"#).is_err());
        assert!(read(br#"{"type":"Blob"}"#).is_err());
        assert!(read(b"").is_err());
    }

    /// A square of two black triangles as a plane contour (zinc values).
    fn square_contour() -> PlaneContour {
        use crate::contour::{
            contour_triangulated_2d, SampleOptions, SampleTriangulation2, SelectedSamples,
        };
        let pts = [p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)];
        let sel = SelectedSamples {
            column: "zinc".into(),
            input: vec![0, 1, 2, 3],
            values: vec![1.0, 1.0, 1.0, 1.0],
            skipped: 0,
        };
        let tri = SampleTriangulation2 {
            points: &pts,
            vertex_of_input: &[0, 1, 2, 3],
            input_of_vertex: &[0, 1, 2, 3],
            triangles: &[[0, 1, 2], [0, 2, 3]],
            neighbors: None,
        };
        contour_triangulated_2d(sel, tri, &SampleOptions::default()).unwrap()
    }

    #[test]
    fn contour_rings_are_closed_and_counter_clockwise() {
        let r = square_contour();
        let v = contour_value(&r, 0.0, false);
        let ring = v["features"][0]["geometry"]["coordinates"][0]
            .as_array()
            .unwrap();
        assert_eq!(ring.len(), 5);
        assert_eq!(ring[0], ring[4]);
        let pts: Vec<Point2> = ring
            .iter()
            .map(|q| p(q[0].as_f64().unwrap(), q[1].as_f64().unwrap()))
            .collect();
        assert_eq!(ring_orientation(&pts[..4]), 1);
        assert_eq!(v["features"][0]["properties"]["threshold"], 0.0);
        assert_eq!(v["features"][0]["properties"]["value"], "zinc");
        let mut out = Vec::new();
        write_contour(&mut out, &r, 0.0, false).unwrap();
        assert_eq!(read(&out).unwrap().polygons.len(), 1);
        let mut out = Vec::new();
        crate::io::json::write_contour_cycles(&mut out, &r).unwrap();
        let j: Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(j["cycles"][0].as_array().unwrap().len(), 4);
        assert_eq!(j["regions"][0]["outer"], 0);
    }

    #[test]
    fn writer_orients_rings_and_round_trips() {
        let outer_cw = vec![p(0., 0.), p(0., 10.), p(10., 10.), p(10., 0.)];
        let hole_ccw = vec![p(2., 2.), p(4., 2.), p(4., 4.)];
        let sh = Shapes2 {
            polygons: vec![Polygon {
                rings: vec![outer_cw, hole_ccw],
            }],
            polylines: vec![Polyline {
                points: vec![p(0.1, 0.2), p(0.3, 0.4)],
                closed: false,
            }],
        };
        let mut out = Vec::new();
        write(&mut out, &sh).unwrap();
        let back = read(&out).unwrap();
        assert_eq!(ring_orientation(&back.polygons[0].rings[0]), 1);
        assert_eq!(ring_orientation(&back.polygons[0].rings[1]), -1);
        assert_eq!(back.polylines, sh.polylines);
    }
}

/// Reads the `Point` and `MultiPoint` geometries of a GeoJSON document (alone or inside
/// features and collections; polygons and lines are skipped) as a point set: 3D when every
/// position has a third number, else 2D (further numbers ignored). Numeric properties that
/// every `Point` feature carries become columns (for example the `value` of rated samples);
/// they are dropped when the document also has `MultiPoint`s, whose positions share one
/// property set. Returns an empty set when the document holds no point.
///
/// ```
/// let doc = br#"{"type":"FeatureCollection","features":[
///   {"type":"Feature","properties":{"value":1.5},"geometry":{"type":"Point","coordinates":[0,1]}},
///   {"type":"Feature","properties":{"value":2.0},"geometry":{"type":"Point","coordinates":[2,3]}}]}"#;
/// let p = morpho::io::geojson::read_points(doc).unwrap();
/// assert_eq!((p.len(), p.dim), (2, 2));
/// assert_eq!(p.columns[0].name, "value");
/// assert_eq!(p.columns[0].values, vec![1.5, 2.0]);
/// ```
pub fn read_points(bytes: &[u8]) -> Result<PointSet> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let v: Value = serde_json::from_slice(bytes)
        .map_err(|e| Error::at_line(e.line() as u64, format!("bad JSON: {e}")))?;
    let mut acc = PointAcc::default();
    if !v.is_array() {
        walk_points(&v, None, &mut acc)?;
        note_input_crs(&v);
    }
    let dim = if !acc.pos.is_empty() && acc.pos.iter().all(|p| p.len() >= 3) {
        3
    } else {
        2
    };
    let mut out = PointSet {
        dim,
        coords: Vec::with_capacity(acc.pos.len() * dim),
        columns: Vec::new(),
    };
    for p in &acc.pos {
        out.coords.extend_from_slice(&p[..dim]);
    }
    if !acc.multi && !acc.props.is_empty() {
        let first = &acc.props[0];
        for key in first.keys() {
            let vals: Option<Vec<f64>> = acc
                .props
                .iter()
                .map(|m| m.get(key).and_then(Value::as_f64).filter(|f| f.is_finite()))
                .collect();
            if let Some(values) = vals {
                out.columns.push(Column {
                    name: key.clone(),
                    values,
                });
            }
        }
    }
    Ok(out)
}

#[derive(Default)]
struct PointAcc {
    pos: Vec<Vec<f64>>,
    props: Vec<serde_json::Map<String, Value>>,
    multi: bool,
}

fn point_position(v: &Value, ctx: &str) -> Result<Vec<f64>> {
    let p = position(v, ctx)?;
    let mut out = vec![p.x, p.y];
    if let Some(z) = v.as_array().and_then(|a| a.get(2)) {
        let z = z
            .as_f64()
            .filter(|f| f.is_finite())
            .ok_or_else(|| Error::format(format!("{ctx}: a coordinate is not a finite number")))?;
        out.push(z);
    }
    Ok(out)
}

fn walk_points(
    v: &Value,
    props: Option<&serde_json::Map<String, Value>>,
    acc: &mut PointAcc,
) -> Result<()> {
    let ty = v
        .get("type")
        .and_then(Value::as_str)
        .ok_or_else(|| Error::format("a GeoJSON object needs a \"type\" string"))?;
    let list = |key: &str| {
        v.get(key)
            .and_then(Value::as_array)
            .ok_or_else(|| Error::format(format!("{ty} without a \"{key}\" array")))
    };
    match ty {
        "FeatureCollection" => {
            for f in list("features")? {
                walk_points(f, None, acc)?;
            }
        }
        "Feature" => {
            if let Some(g) = v.get("geometry").filter(|g| !g.is_null()) {
                walk_points(g, v.get("properties").and_then(Value::as_object), acc)?;
            }
        }
        "GeometryCollection" => {
            for g in list("geometries")? {
                walk_points(g, None, acc)?;
            }
        }
        "Point" => {
            acc.pos.push(point_position(coords(v, ty)?, ty)?);
            acc.props.push(props.cloned().unwrap_or_default());
        }
        "MultiPoint" => {
            let ps = coords(v, ty)?
                .as_array()
                .ok_or_else(|| Error::format("MultiPoint: expected an array of positions"))?;
            for p in ps {
                acc.pos.push(point_position(p, ty)?);
            }
            acc.multi |= !ps.is_empty();
        }
        _ => {}
    }
    Ok(())
}

/// Writes a point set as a `FeatureCollection` of `Point` features, one per point, with the
/// point set's columns as numeric properties (a non-finite value becomes `null`); 3D points
/// keep their z as the third coordinate. The crs member follows [`set_crs`].
pub fn write_points(w: &mut dyn Write, pts: &PointSet) -> Result<()> {
    let mut features = Vec::with_capacity(pts.len());
    for i in 0..pts.len() {
        let p = pts.point(i);
        if p.iter().any(|c| !c.is_finite()) {
            return Err(Error::invalid("cannot write a non-finite coordinate"));
        }
        let mut props = serde_json::Map::new();
        for c in &pts.columns {
            let x = c.values[i];
            props.insert(
                c.name.clone(),
                if x.is_finite() { json!(x) } else { Value::Null },
            );
        }
        features.push(json!({
            "type": "Feature",
            "properties": props,
            "geometry": {"type": "Point", "coordinates": p},
        }));
    }
    let doc = json!({"type": "FeatureCollection", "features": features});
    super::json::write_value(w, &with_crs(doc))
}
