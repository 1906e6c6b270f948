"""The components' layers hold (docs/developer.md, "Components"): a lower component never includes a
higher one's header, no function outside src/app/ takes the run-wide context MMCtx, and app's header
stays private to app. A C file cannot call another component's function without its prototype
(-Wall refuses an implicit declaration), so the includes are the call graph's arrows."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parent.parent
LAYERS = ["sys", "mesh", "obstacle", "fem", "contact", "friction", "ts", "io", "app"]
# mesh and obstacle stand side by side on one level
RANK = {c: i for i, c in enumerate(LAYERS)}
RANK["obstacle"] = RANK["mesh"]
# the public headers of include/ and the component each belongs to
PUBLIC = {"mmbase.h": "sys", "sys.h": "sys", "mesh.h": "mesh", "obstacle.h": "obstacle", "fem.h": "fem",
          "contact.h": "contact", "friction.h": "friction", "ts.h": "ts", "io.h": "io"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def component_of(path):
    rel = path.relative_to(ROOT)
    if rel.parts[0] == "include":
        assert rel.name in PUBLIC, f"{rel}: a header in include/ that belongs to no component"
        return PUBLIC[rel.name]
    assert rel.parts[0] == "src" and rel.parts[1] in RANK, f"{rel}: a source outside the components"
    return rel.parts[1]


def sources():
    return sorted(p for d in ("src", "include") for p in (ROOT / d).rglob("*") if p.suffix in (".c", ".h"))


def resolve(src, name):
    """The project header an include names: beside the file first, then include/ (the compiler's order)."""
    for cand in (src.parent / name, ROOT / "include" / name):
        if cand.exists():
            return cand.resolve()
    return None  # a system or PETSc header


def test_no_component_includes_a_higher_one():
    upward = []
    for src in sources():
        me = component_of(src)
        for name in INCLUDE.findall(src.read_text()):
            hdr = resolve(src, name)
            if hdr is None:
                continue
            other = component_of(hdr)
            if RANK[other] > RANK[me] or (RANK[other] == RANK[me] and other != me):
                upward.append(f"{src.relative_to(ROOT)} ({me}) includes {name} ({other})")
    assert not upward, "includes that run back up:\n" + "\n".join(upward)


def test_headers_private_to_a_component_stay_in_it():
    # an *impl.h or a header beside the code is included only from its own component's folder
    leaks = []
    for src in sources():
        for name in INCLUDE.findall(src.read_text()):
            hdr = resolve(src, name)
            if hdr is None or hdr.parent == ROOT / "include":
                continue
            if component_of(hdr) != component_of(src):
                leaks.append(f"{src.relative_to(ROOT)} includes {hdr.relative_to(ROOT)}")
    assert not leaks, "private headers used outside their component:\n" + "\n".join(leaks)


def test_only_app_takes_the_run_context():
    # a definition or prototype with an MMCtx parameter, outside src/app/
    takes = re.compile(r"\b\w+\s*\([^;{)]*\bMMCtx\s*\*", re.S)
    found = [str(p.relative_to(ROOT)) for p in sources()
             if component_of(p) != "app" and ("MMCtx" in p.read_text() and takes.search(p.read_text()))]
    assert not found, "MMCtx outside src/app/: " + ", ".join(found)
    mentions = [str(p.relative_to(ROOT)) for p in sources() if component_of(p) != "app" and "MMCtx" in p.read_text()]
    assert not mentions, "MMCtx named outside src/app/: " + ", ".join(mentions)
