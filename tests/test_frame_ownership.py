"""The contact frame's owner (docs/developer.md, "The contact frame"), no run: the w-frame operators
are read through contact (MMContactGetOperators), never in fem's MMOperators, by the components
above contact; no file outside contact turns w-frame data by hand (contact turns what a holder
registered once, src/contact/interface/held.c); and the stepper's registration is the one file
outside contact that registers. The frame itself, Q and N, is contact's: fem holds none of it
and turns vectors through the ops table contact installs (MMFESetFrame)."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parent.parent
# the w-frame fields of MMOperators (src/fem/femimpl.h), through any pointer or struct named op
WFRAME = re.compile(r"\bop(?:->|\.)(K|Mstar|Q|N|Ninv|load|lift|mass_star|mass_star_inv|massless)\b")
ABOVE = ("friction", "ts", "io", "app")


def sources(components):
    return sorted(p for c in components for p in (ROOT / "src" / c).rglob("*") if p.suffix in (".c", ".h"))


def test_no_w_frame_field_read_above_contact():
    bad = [f"{p.relative_to(ROOT)}:{s[:m.start()].count(chr(10)) + 1}: op {m.group(1)}"
           for p in sources(ABOVE) for s in [p.read_text()] for m in WFRAME.finditer(s)]
    assert not bad, "read the w-frame operators through MMContactGetOperators:\n" + "\n".join(bad)


def test_no_hand_written_turn_outside_contact():
    turn = re.compile(r"\b(MMRotateP1|MMContactFramesRotate\w*|MMMomentaDestroy)\s*\(")
    allowed = {"src/ts/momenta.c", "src/ts/context.c", "src/ts/newmarkimpl.h"}  # the momenta's own rebuild, destroy, prototype
    bad = [f"{p.relative_to(ROOT)}: {m.group(1)}" for p in sources(ABOVE)
           if str(p.relative_to(ROOT)) not in allowed for m in turn.finditer(p.read_text())]
    assert not bad, "contact turns the w-frame data it holds (MMContactFramesAddVec):\n" + "\n".join(bad)


def test_one_registration_outside_contact():
    reg = re.compile(r"\bMMContactFrames(AddVec|AddMat)\s*\(")
    files = {str(p.relative_to(ROOT)) for p in sources(ABOVE + ("fem",)) if reg.search(p.read_text())}
    assert files <= {"src/ts/nonlinear.c"}, f"w-frame data registered outside the stepper's RegisterFrameData: {sorted(files)}"


def test_fem_holds_no_frame():
    """The frame (Q, the contact pairs' N and N^{-1}, their scratch) is contact's
    (src/contact/frame/transform.c): fem's MMOperators holds none of it, fem turns vectors through
    the ops table contact installs (MMFESetFrame), and no file reads them in fem's operators."""
    header = (ROOT / "src" / "fem" / "femimpl.h").read_text()  # the struct is private to fem
    body = header[header.index("struct _p_MMOperators {"):]
    body = body[:body.index("\n};")]
    body = re.sub(r"/\*.*?\*/", "", body, flags=re.S)  # the fields, not their comments
    held = [f for f in ("Q", "N", "Ninv", "pair_work") if re.search(r"\b" + f + r"\b\s*[;,]", body)]
    assert not held, f"fem's MMOperators holds the frame's {held}: contact's MMContactTransform does"
    assert "MMFrame   frame;" in body, "fem's operators reach the frame through contact's ops table (MMFrame)"
    field = re.compile(r"\bop(?:->|\.)(Q|N|Ninv|pair_work)\b")
    bad = [f"{p.relative_to(ROOT)}:{s[:m.start()].count(chr(10)) + 1}: op {m.group(1)}"
           for p in sources(("fem", "contact") + ABOVE) for s in [p.read_text()] for m in field.finditer(s)]
    assert not bad, "the frame's Q and N are contact's (ct->transform):\n" + "\n".join(bad)
    fem = [str(p.relative_to(ROOT)) for p in sources(("fem",)) if re.search(r"\bMat(Mult|MultTranspose)\s*\([^,]*->(Q|N|Ninv)\b", p.read_text())]
    assert not fem, f"fem multiplies by the frame's matrices itself: {fem}"


def test_fem_k_load_and_lift_stay_cartesian():
    """fem holds nothing in the w-frame: it hands its assembled K and M over to contact
    (MMFEHandMatrices, called once, in src/contact/frame/frame.c), which turns them in place, so no
    Cartesian copy of K outlives the set-up; fem's load and lift stay Cartesian and contact keeps its
    own w-frame ones (Q^T, then N^T, of fem's); the loads in time set contact's (MMLoadsSetUp hands
    them). Outside fem.c, fem's K and M are never named, and its load and lift only read (contact
    takes them through MMFEGetLoad and MMFEGetLift)."""
    use = re.compile(r"\bop(?:->|\.)(K|M|load|lift)\b")
    # a copy's layout, and the read-only handles of MMFEGetLoad and MMFEGetLift (src/fem/fem_object.c)
    read = re.compile(r"VecDuplicate\([\w>.-]*op(?:->|\.)(load|lift),|^\s*\*(load|lift) = op->(load|lift);$")
    bad = [f"{p.relative_to(ROOT)}:{n}: {line.strip()}"
           for p in sources(("fem", "contact") + ABOVE) if str(p.relative_to(ROOT)) != "src/fem/fem.c"
           for n, line in enumerate(p.read_text().splitlines(), 1) if use.search(line) and not read.search(line)]
    assert not bad, "fem's K and M are handed to contact (MMFEHandMatrices); the w-frame K, M, load and lift are contact's:\n" + "\n".join(bad)
    hand = [str(p.relative_to(ROOT)) for p in sources(("fem", "contact") + ABOVE) if "MMFEHandMatrices(" in p.read_text()]
    assert hand == ["src/contact/frame/frame.c", "src/fem/fem.c"], hand
    fem = (ROOT / "src" / "fem" / "fem.c").read_text()
    body = fem[fem.index("PetscErrorCode MMFEHandMatrices("):]
    body = body[:body.index("\n}\n")]
    assert "op->K = NULL;" in body and "op->M = NULL;" in body, "fem keeps no reference to what it hands over"
