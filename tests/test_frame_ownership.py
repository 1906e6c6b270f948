"""The contact frame's owner (docs/developer.md, "The contact frame"), no run: the w-frame operators
are read through contact (MMContactGetOperators), never in fem's MMOperators, by the components
above contact; no file outside contact turns w-frame data by hand (contact turns what a holder
registered once, src/contact/interface/held.c); and the stepper's registration is the one file
outside contact that registers."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parent.parent
# the w-frame fields of MMOperators (include/fem.h), through any pointer or struct named op
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
