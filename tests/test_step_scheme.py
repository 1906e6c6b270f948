"""The time scheme is the stepper's alone (docs/developer.md, "The step's data flow"): contact and
friction take the step's offset u^n + dt/2 v^n, its scale 2/dt and the velocity of w from the
stepper (MMStepOffset), and never read u^n or v^n; TSStep_Newmark is one skeleton for the linear and
the finite-strain steps, which differ by their law's ops (src/ts/step_laws.c), with no branch on the
law. No run: the sources are read."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parent.parent


def sources(*components):
    for c in components:
        yield from sorted((ROOT / "src" / c).rglob("*.[ch]"))
        yield ROOT / "include" / f"{c}.h"


def code(path):
    """The file without its comments: a comment may describe the scheme, code may not rebuild it."""
    text = path.read_text()
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def test_contact_and_friction_never_read_the_step_start():
    found = []
    for src in sources("contact", "friction"):
        for name in ("u_old", "v_old"):
            if re.search(rf"\b{name}\b", code(src)):
                found.append(f"{src.relative_to(ROOT)}: {name}")
    assert not found, "the step's start read below the stepper:\n" + "\n".join(found)


def test_contact_and_friction_do_not_rebuild_the_offset_or_the_velocity():
    # the offset u + 0.5 dt v from the step's dt, and the velocity 2/dt (w - u) - v
    patterns = [r"0\.5\s*\*\s*ct->Kt_dt", r"2(\.0)?\s*/\s*(cn\.)?dt\s*\*\s*\(", r"2\.0\s*/\s*cn\.dt"]
    found = []
    # frames.c: the frames that follow take the predicted midpoint in Cartesian components (see the docs)
    for src in sources("contact", "friction"):
        if src.name == "frames.c":
            continue
        for p in patterns:
            if re.search(p, code(src)):
                found.append(f"{src.relative_to(ROOT)}: {p}")
    assert not found, "the scheme rebuilt below the stepper:\n" + "\n".join(found)


def test_the_step_has_no_branch_on_the_law():
    text = code(ROOT / "src" / "ts" / "newmark.c")
    body = re.search(r"static PetscErrorCode TSStep_Newmark\(TS ts\)\s*\{(.*?)\n\}", text, flags=re.S)
    assert body, "TSStep_Newmark not found in src/ts/newmark.c"
    assert "finite" not in body.group(1), "TSStep_Newmark branches on the law: use its ops (src/ts/step_laws.c)"
    assert "nm->law->solve" in body.group(1)
