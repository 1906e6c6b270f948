#!/usr/bin/env bash
# mmcontact against GetFEM on the same mesh, as whole processes (start to exit), one after the other on
# one core each: the D2 ball (R 1, E 1000, nu 0.3, rho 1, v0 (0.5, 0, -1), gap 0.01) at mesh size H,
# Coulomb mu, dt, to time T. The GetFEM side is scripts/peers/getfem_ball_impact.py: the same modified
# mass, the trapezoidal Newmark step and exact nodal contact by GetFEM's own semismooth Newton, with the
# friction law on the end-of-step velocity as ours (--slip velocity: the same discrete problem; its
# docstring says how, and what it checks). Prints both processes' wall times, both time loops, and the
# ratios: docs/friction.md, "Against GetFEM, the same ball to the same time".
#   Usage: scripts/getfem_compare.sh [H 0.07] [MU 0.2] [DT 4e-3] [T 0.08]
# It needs python3-getfem (Debian; installed on demand with apt-get when run as root). A GetFEM run
# at H 0.07 takes about three minutes.
set -eu
H=${1:-0.07}; MU=${2:-0.2}; DT=${3:-4e-3}; T=${4:-0.08}
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
if ! /usr/bin/python3 -s -c "import getfem" 2>/dev/null; then
  if [ "$(id -u)" = 0 ]; then apt-get install -y python3-getfem >/dev/null
  else echo "getfem_compare: python3-getfem is missing: sudo apt-get install python3-getfem" >&2; exit 1; fi
fi
make -C "$root" -s mmcontact >/dev/null
gmsh -3 "$root/meshes/ball.geo" -setnumber H "$H" -o "$work/ball.msh" -v 0 >/dev/null

# timed OUT CMD...: CMD's output into OUT, its wall time (s) on stdout
timed() { local out=$1 t0 t1; shift; t0=$(date +%s.%N); "$@" > "$out" 2>&1 || { tail "$out" >&2; return 1; }; t1=$(date +%s.%N); echo "$t1 - $t0" | bc -l; }
mm_wall=$(timed "$work/mm.log" mpiexec -n 1 "$root/mmcontact" -options_file "$root/options/d2_ball.opts" -mesh "$work/ball.msh" \
  -mu "$MU" -ts_dt "$DT" -ts_max_time "$T" -output_every 0 -output_dir "$work/mm")
gf_wall=$(timed "$work/gf.log" /usr/bin/python3 -s "$root/scripts/peers/getfem_ball_impact.py" --msh "$work/ball.msh" --h "$H" \
  --dt "$DT" --T "$T" --mu "$MU" --slip velocity --csv "$work/gf.csv")

/usr/bin/python3 -s - "$work/mm.log" "$work/gf.log" "$mm_wall" "$gf_wall" "$H" "$MU" "$DT" "$T" <<'PY'
import re, sys
mm, gf = open(sys.argv[1]).read(), open(sys.argv[2]).read()
mm_wall, gf_wall = float(sys.argv[3]), float(sys.argv[4])
m = re.search(r"(\d+) steps to t = \S+ in ([0-9.e+-]+) s wall", mm)
g = re.search(r"loop_wall_s=([0-9.e+-]+)", gf)
ndofs = re.search(r"ndofs=(\d+)", gf)
print(f"D2 ball H {sys.argv[5]} mu {sys.argv[6]} dt {sys.argv[7]} to t = {sys.argv[8]} ({ndofs.group(1) if ndofs else '?'} dofs, {m.group(1)} steps)")
print(f"  whole process: mmcontact {mm_wall:.2f} s, GetFEM {gf_wall:.2f} s: {gf_wall / mm_wall:.1f} x")
if g:
    print(f"  time loop:     mmcontact {float(m.group(2)):.2f} s, GetFEM {float(g.group(1)):.2f} s: {float(g.group(1)) / float(m.group(2)):.1f} x")
PY
