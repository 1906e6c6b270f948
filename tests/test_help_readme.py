"""-help is the reference manual; README.md must document every option it lists."""
import os
import re
import subprocess

from conftest import EXE, ROOT


def test_every_help_option_is_in_readme():
    out = subprocess.run([EXE, "-options_file", "options/b1_bar.opts", "-traction", "sides", "-bodies", "body", "-body_body_group", "body", "-help", "-ts_max_steps", "0",
                          "-output_dir", "/tmp/mmcontact-help"], cwd=ROOT, capture_output=True).stdout.decode(errors="replace")  # PETSc 3.18 prints an uninitialized buffer for -dm_plex_boundary_label
    section = out.split("mmcontact: modified-mass dynamic contact")[1].split("-------")[0]
    options = set(re.findall(r"^\s+(-[a-z_0-9A-Z]+)", section, re.M))
    assert len(options) >= 25
    readme = open(os.path.join(ROOT, "README.md")).read()
    for opt in options:
        generic = re.sub(r"^-(dirichlet|traction|body)_(right|sides|body)_", r"-\1_NAME_", opt)
        assert generic in readme, opt
    # every help string is there
    assert section.count("(None)") == len(options)
