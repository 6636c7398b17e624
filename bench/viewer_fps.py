#!/usr/bin/env python3
"""Issue 22: how fast a `morpho view` page opens and orbits in headless Chromium (software GL).

    python3 bench/viewer_fps.py [--page PAGE.html] [--ply MESH.ply] [--seconds 4] [--lod N]

Without --page it makes the ~1M-triangle contour surface of the MNI brain template
(/work/shared/data, level 170: 949 300 triangles), its page (`morpho view`), and measures it.
Chromium runs headless with SwiftShader (`--use-angle=swiftshader`), driven over the DevTools
protocol on a pipe (no network, no extra packages). The page's `#selftest=` hook does the
timing inside the browser:

- ready_ms: navigation start → first frame drawn and finished (readPixels), the proxy when the
  mesh has one; full_ms: → the full-detail frame on screen (progressive refinement);
- orbit: a scripted orbit of --seconds, one camera step per requestAnimationFrame callback,
  drawing what a drag draws (the proxy at half the resolution): fps = frames / elapsed, with
  frame-interval median, 95th percentile and maximum; orbit_fullres: the proxy at full
  resolution; orbit_full: every triangle at full resolution;
- renderer: WebGL's UNMASKED_RENDERER string (which GL backend Chromium used).

It also prints the page size against a binary PLY with float32 positions and int32 indices
(header + 12 V + 13 T bytes) and the load average before and after (the machine is shared).
"""
import argparse, json, os, re, shlex, subprocess, sys, tempfile, time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MORPHO = os.environ.get("MORPHO", os.path.join(ROOT, "target", "release", "morpho"))
VOLUME = "/work/shared/data/volumes/mni_icbm152_t1_2009a_197x233x189.nhdr"


class Chrome:
    """Chromium headless, DevTools protocol over --remote-debugging-pipe (fds 3 and 4)."""

    def __init__(self, profile, size=(1024, 768)):
        args = ["chromium", "--headless", "--no-sandbox", "--disable-gpu", "--use-angle=swiftshader",
                "--enable-unsafe-swiftshader", "--no-first-run", "--disable-background-networking",
                "--disable-component-update", "--disable-sync", "--remote-debugging-pipe",
                f"--window-size={size[0]},{size[1]}", f"--user-data-dir={profile}", "about:blank"]
        cmd = "exec " + " ".join(map(shlex.quote, args)) + " 3<&0 4>&1 </dev/null >/dev/null 2>/dev/null"
        self.p = subprocess.Popen(["sh", "-c", cmd], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        self.buf, self.id, self.events = b"", 0, []

    def recv(self):
        while b"\0" not in self.buf:
            c = os.read(self.p.stdout.fileno(), 1 << 20)
            if not c:
                raise RuntimeError("chromium closed the DevTools pipe")
            self.buf += c
        m, self.buf = self.buf.split(b"\0", 1)
        return json.loads(m)

    def call(self, method, params=None, session=None):
        self.id += 1
        msg = {"id": self.id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        self.p.stdin.write(json.dumps(msg).encode() + b"\0")
        self.p.stdin.flush()
        while True:
            m = self.recv()
            if m.get("id") == self.id:
                if "error" in m:
                    raise RuntimeError(f"{method}: {m['error']}")
                return m["result"]
            self.events.append(m)

    def wait_event(self, name, timeout=60):
        t0 = time.time()
        while time.time() - t0 < timeout:
            for i, e in enumerate(self.events):
                if e.get("method") == name:
                    return self.events.pop(i)
            self.events.append(self.recv())
        raise RuntimeError(f"no {name} within {timeout} s")

    def page(self):
        tid = [t for t in self.call("Target.getTargets")["targetInfos"] if t["type"] == "page"][0]["targetId"]
        return self.call("Target.attachToTarget", {"targetId": tid, "flatten": True})["sessionId"]

    def close(self):
        try:
            self.call("Browser.close")
        except Exception:
            pass
        self.p.wait(10)


def ply_counts(path):
    head = open(path, "rb").read(4096).split(b"end_header")[0].decode("latin-1")
    v = int(re.search(r"element vertex (\d+)", head).group(1))
    t = int(re.search(r"element face (\d+)", head).group(1))
    return v, t


def ply_f32_i32_bytes(v, t):
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\n"
              "property float y\nproperty float z\nelement face %d\n"
              "property list uchar int vertex_indices\nend_header\n" % (v, t))
    return len(header) + 12 * v + 13 * t


def measure(page, steps, profile):
    c = Chrome(profile)
    try:
        s = c.page()
        c.call("Page.enable", session=s)
        t0 = time.time()
        c.call("Page.navigate", {"url": "file://" + os.path.abspath(page) + "#selftest=" + steps}, session=s)
        c.wait_event("Page.loadEventFired", 120)
        load_s = time.time() - t0
        r = c.call("Runtime.evaluate", {"expression": "window.morphoSelftest", "awaitPromise": True,
                                        "returnByValue": True}, session=s)
        res = r["result"].get("value")
        if res is None:
            raise RuntimeError(f"selftest failed: {r}")
        res["load_event_s"] = load_s
        return res
    finally:
        c.close()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--page")
    ap.add_argument("--ply", help="the mesh the page shows (for the size comparison)")
    ap.add_argument("--seconds", type=float, default=4.0)
    ap.add_argument("--lod", type=int, help="passed to morpho view")
    ap.add_argument("--level", type=float, default=170.0)
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="viewer_fps_")
    if a.page is None:
        a.ply = os.path.join(tmp, "brain.ply")
        subprocess.run([MORPHO, "isosurface", VOLUME, "--level", str(a.level), "--normals", "none",
                        "-o", a.ply], check=True, stderr=subprocess.DEVNULL)
        a.page = os.path.join(tmp, "brain.html")
        cmd = [MORPHO, "view", a.ply, "-o", a.page]
        if a.lod is not None:
            cmd += ["--lod", str(a.lod)]
        t = time.time()
        subprocess.run(cmd, check=True, stderr=subprocess.DEVNULL)
        gen_s = time.time() - t
    else:
        gen_s = None
    load_before = os.getloadavg()
    r = measure(a.page, f"full,fps:{a.seconds:g},fpsfullres:{a.seconds:g},fpsfull:{min(a.seconds, 3):g}", os.path.join(tmp, "profile"))
    load_after = os.getloadavg()
    out = {"page": a.page, "page_bytes": os.path.getsize(a.page), "page_seconds": gen_s,
           "cores": os.cpu_count(), "loadavg_before": load_before, "loadavg_after": load_after,
           "chromium": subprocess.run(["chromium", "--version"], capture_output=True, text=True).stdout.strip(),
           **r}
    if a.ply:
        v, t = ply_counts(a.ply)
        out.update(vertices=v, triangles=t, ply_f32_i32_bytes=ply_f32_i32_bytes(v, t))
        out["page_over_ply"] = out["page_bytes"] / out["ply_f32_i32_bytes"]
    print(json.dumps(out, indent=1))
    o, f, fr = r.get("orbit", {}), r.get("orbit_full", {}), r.get("orbit_fullres", {})
    print(f"\nrenderer: {r.get('renderer')}\nfirst frame {r.get('ready_ms', 0):.0f} ms, full detail "
          f"{(r.get('full_ms') or 0):.0f} ms after navigation start\norbit (proxy while moving): "
          f"{o.get('fps', 0):.1f} fps (median {o.get('median_ms', 0):.1f} ms, p95 {o.get('p95_ms', 0):.1f} ms)"
          f"\norbit, proxy at full resolution: {fr.get('fps', 0):.1f} fps"
          f"\norbit drawing every triangle: {f.get('fps', 0):.1f} fps\nload average before "
          f"{load_before[0]:.2f}, after {load_after[0]:.2f} on {os.cpu_count()} cores", file=sys.stderr)
    if "page_over_ply" in out:
        print(f"page {out['page_bytes']} B = {out['page_over_ply']:.3f} x PLY float32/int32 "
              f"({out['ply_f32_i32_bytes']} B)", file=sys.stderr)
    if r.get("errors"):
        print("console errors:", r["errors"], file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
