"""fem's operators are an opaque object, as the other components are (docs/developer.md, "Components";
issue 49): include/fem.h declares the handle MMOperators alone, its struct lives in fem's private
header src/fem/femimpl.h, and no file outside src/fem/ names one of its fields: the other components
read what they need through fem's functions (MMFEGetDM, MMFEGetDimension, ...). No run."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parent.parent
FEM = ROOT / "src" / "fem"
IMPL = FEM / "femimpl.h"
STRUCT = re.compile(r"\bstruct\s+_p_MMOperators\s*\{")


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def sources():
    return sorted(p for d in ("src", "include") for p in (ROOT / d).rglob("*") if p.suffix in (".c", ".h"))


def outside_fem():
    return [p for p in sources() if FEM not in p.parents]


def fields():
    """The struct's field names, read from its definition (so a new field is covered without editing this test)."""
    text = strip_comments(IMPL.read_text())
    m = STRUCT.search(text)
    assert m, "src/fem/femimpl.h defines struct _p_MMOperators"
    depth, i = 1, m.end()
    while depth:
        depth += {"{": 1, "}": -1}.get(text[i], 0)
        i += 1
    body = text[m.end():i - 1]
    names = set()
    for decl in body.split(";"):
        decl = re.sub(r"\[[^\]]*\]", "", decl).strip()
        if not decl:
            continue
        # "Type a, *b" or "Type a": every declarator's name
        head, *rest = decl.split(",")
        names.update(re.findall(r"(\w+)\s*$", head))
        for r in rest:
            names.update(re.findall(r"(\w+)\s*$", r))
    assert {"dm", "dim", "dm_scalar", "cells"} <= names, names
    return names


def test_handle_public_struct_private():
    header = (ROOT / "include" / "fem.h").read_text()
    assert re.search(r"typedef\s+struct\s+_p_MMOperators\s*\*\s*MMOperators\s*;", header), \
        "include/fem.h declares the handle: typedef struct _p_MMOperators *MMOperators;"
    where = [str(p.relative_to(ROOT)) for p in sources() if STRUCT.search(strip_comments(p.read_text()))]
    assert where == ["src/fem/femimpl.h"], f"struct _p_MMOperators is defined in fem's private header alone: {where}"
    # no public header spells the struct's layout some other way (a typedef of an anonymous struct named MMOperators)
    for hdr in (ROOT / "include").glob("*.h"):
        assert not re.search(r"\}\s*MMOperators\s*;", strip_comments(hdr.read_text())), f"{hdr.name} defines MMOperators' fields"


def test_private_header_not_included_outside_fem():
    inc = re.compile(r'^\s*#\s*include\s+"([^"]*femimpl\.h)"', re.M)
    bad = [str(p.relative_to(ROOT)) for p in outside_fem() if inc.search(p.read_text())]
    assert not bad, f"src/fem/femimpl.h is fem's private header, included outside src/fem: {bad}"


def test_no_field_read_outside_fem():
    """Every name an MMOperators is held under outside fem (op, ct->op, a struct's member...), and the
    usual name op: none is followed by -> or . and one of the struct's fields."""
    names = fields()
    holders = {"op"}
    for p in outside_fem():
        holders.update(re.findall(r"\bMMOperators\s*\**\s*(\w+)\s*[;,=)\[]", strip_comments(p.read_text())))
    holders.discard("MMOperators")
    access = re.compile(r"\b(" + "|".join(sorted(holders)) + r")\s*\)?\s*(?:->|\.)\s*(\w+)\b")
    bad = []
    for p in outside_fem():
        text = strip_comments(p.read_text())
        for m in access.finditer(text):
            if m.group(2) in names:
                line = text[:m.start()].count("\n") + 1
                bad.append(f"{p.relative_to(ROOT)}:{line}: {m.group(0)}")
    assert not bad, "fem's operators are opaque: read them through fem's functions (MMFEGetDM, ...):\n" + "\n".join(bad)
