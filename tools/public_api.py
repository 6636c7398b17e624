#!/usr/bin/env python3
"""List the public API of the `morpho` library crate from rustdoc's JSON output.

Usage (stable toolchain; rustdoc's JSON output is unstable, hence RUSTC_BOOTSTRAP):
    RUSTC_BOOTSTRAP=1 cargo rustdoc -p morpho --lib -- -Z unstable-options --output-format json
    python3 tools/public_api.py target/doc/morpho.json [--list]

Walks from the crate root through public modules and `pub use` re-exports and prints one
line per reachable public item path (modules, types, functions, constants, fields, variants,
inherent methods), then the counts per kind. An item reachable by two paths counts once.
"""
import json
import sys
from collections import Counter

def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "target/doc/morpho.json"
    listing = "--list" in sys.argv
    d = json.load(open(path))
    idx = d["index"]
    seen = {}

    def kind(it):
        return next(iter(it["inner"].keys()))

    def visit(iid, prefix):
        it = idx.get(str(iid))
        if it is None:
            return
        k = kind(it)
        if k == "use":
            u = it["inner"]["use"]
            target = u.get("id")
            if target is None or str(target) not in idx:
                return
            if u.get("is_glob"):
                t = idx[str(target)]
                if kind(t) == "module":
                    for c in t["inner"]["module"]["items"]:
                        visit(c, prefix)
                return
            name = u["name"]
            t = idx[str(target)]
            visit_named(target, t, prefix + [name])
            return
        if it.get("visibility") != "public":
            return
        visit_named(iid, it, prefix + [it["name"]])

    def visit_named(iid, it, p):
        k = kind(it)
        if it.get("attrs") and any("doc(hidden)" in str(a) for a in it["attrs"]):
            return
        key = str(iid)
        if key in seen:
            return
        seen[key] = ("::".join(p), k)
        inner = it["inner"][k]
        if k == "module":
            for c in inner["items"]:
                visit(c, p)
        elif k in ("struct", "enum", "union", "trait"):
            if k == "struct":
                kd = inner.get("kind", {})
                if isinstance(kd, dict) and "plain" in kd:
                    for f in kd["plain"]["fields"]:
                        fi = idx.get(str(f))
                        if fi and fi.get("visibility") == "public":
                            seen[str(f)] = ("::".join(p + [fi["name"]]), "field")
            if k == "enum":
                for v in inner.get("variants", []):
                    vi = idx.get(str(v))
                    if vi:
                        seen[str(v)] = ("::".join(p + [vi["name"]]), "variant")
            for imp in inner.get("impls", []):
                ii = idx.get(str(imp))
                if not ii:
                    continue
                im = ii["inner"]["impl"]
                if im.get("trait") is not None or im.get("is_synthetic") or im.get("blanket_impl"):
                    continue
                for m in im["items"]:
                    mi = idx.get(str(m))
                    if mi and mi.get("visibility") == "public":
                        if mi.get("attrs") and any("doc(hidden)" in str(a) for a in mi["attrs"]):
                            continue
                        seen[str(m)] = ("::".join(p + [mi["name"]]), kind(mi))

    root = idx[str(d["root"])]
    for c in root["inner"]["module"]["items"]:
        visit(c, ["morpho"])
    if listing:
        for p, k in sorted(seen.values()):
            print(f"{k:10} {p}")
    counts = Counter(k for _, k in seen.values())
    print("total", len(seen), dict(sorted(counts.items())))

main()
