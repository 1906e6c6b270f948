"""-help is the reference manual; README.md must document every option it lists."""
import os
import re
import subprocess

from conftest import EXE, ROOT


def test_every_help_option_is_in_readme():
    out = subprocess.run([EXE, "-options_file", "options/b1_bar.opts", "-traction", "sides", "-bodies", "body", "-body_body_group", "body", "-help", "-ts_max_steps", "0",
                          "-output_dir", "/tmp/mmcontact-help"], cwd=ROOT, capture_output=True).stdout.decode(errors="replace")  # PETSc 3.18 prints an uninitialized buffer for -dm_plex_boundary_label
    # the application's own options, and those of the objects it reads the problem into
    headings = ("mmcontact: modified-mass dynamic contact", "mmcontact: bodies", "mmcontact: boundary conditions and loads")
    section = "".join(out.split(h)[1].split("-------")[0] for h in headings)
    options = set(re.findall(r"^\s+(-[a-z_0-9A-Z]+)", section, re.M))
    assert len(options) >= 25
    readme = open(os.path.join(ROOT, "README.md")).read()
    for opt in options:
        generic = re.sub(r"^-(dirichlet|traction|body)_(right|sides|body)_", r"-\1_NAME_", opt)
        generic = re.sub(r"^-(dirichlet|traction)_NAME_(amplitude)(_time|_table)?$", r"-\1_NAME_\2", generic)
        assert generic in readme, opt
    # every help string is there
    assert section.count("(None)") == len(options)


def test_every_obstacle_option_is_in_readme():
    """Each obstacle reads its options under its prefix -obstacle_NAME_, in its own -help heading: for
    every registered shape, every option that heading lists is in README.md as -obstacle_NAME_...,
    and the -obstacles help names every shape."""
    readme = open(os.path.join(ROOT, "README.md")).read()
    types = ("plane", "sphere", "circle", "cylinder", "box")
    for t in types:
        out = subprocess.run([EXE, "-options_file", "options/ball_bowl.opts", "-obstacles", "o", "-obstacle_o_type", t, "-help", "-ts_max_steps", "0",
                              "-output_dir", "/tmp/mmcontact-help"], cwd=ROOT, capture_output=True).stdout.decode(errors="replace")
        section = out.split("mmcontact: obstacle o:")[1].split("-------")[0]
        options = set(re.findall(r"^\s+(-[a-z_0-9A-Z]+)", section, re.M))
        assert "-obstacle_o_type" in options and len(options) >= 6, (t, options)
        for opt in options:
            assert opt.replace("-obstacle_o_", "-obstacle_NAME_") in readme, (t, opt)
        assert "-obstacle_NAME_type %s" % "|".join(types) in out


def test_help_intro_is_the_readmes():
    """`-help intro` describes the program from the same text as README.md's "-help intro" block:
    the two are identical, line for line (issue 38: it still described the fixed point alone)."""
    out = subprocess.run([EXE, "-help", "intro"], cwd=ROOT, capture_output=True).stdout.decode(errors="replace")
    intro = out.split("\n\n----")[0].splitlines()
    readme = open(os.path.join(ROOT, "README.md")).read()
    block = readme.split("<!-- help intro -->\n")[1].split("\n<!-- /help intro -->")[0].splitlines()
    assert [l[4:] for l in block] == intro and all(l.startswith("    ") for l in block)
    for what in ("semismooth Newton", "-bodies", "-contact_pairs", "damping", "amplitude", "stress"):
        assert what in out, what


def test_readme_states_the_units():
    """One paragraph on units: any consistent set, and in 2D everything per unit thickness."""
    readme = open(os.path.join(ROOT, "README.md")).read()
    units = [p for p in readme.split("\n\n") if p.startswith("**Units.**")]
    assert len(units) == 1 and "consistent" in units[0] and "per unit thickness" in units[0]
