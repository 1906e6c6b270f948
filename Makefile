# mmcontact: build, meshes, showcase run, tests, benchmarks.
PETSC_DIR ?= /usr/lib/petsc
# PETSc's variables exist only once `deps` has installed petsc-dev: `run`, `check` and `bench`
# install first and then build in a sub-make, which reads them.
PETSC_VARIABLES := $(wildcard ${PETSC_DIR}/lib/petsc/conf/variables)
ifneq (${PETSC_VARIABLES},)
include ${PETSC_VARIABLES}
endif

# PETSc's conf/variables defines MPIEXEC and PYTHON: ours have their own names
MM_MPIEXEC ?= mpiexec $(if $(filter 0,$(shell id -u)),--allow-run-as-root)
MM_PYTHON ?= /usr/bin/python3 -s
NP      ?= 2

SRC  := $(shell find src -name '*.c' | sort)
OBJ  := $(SRC:src/%.c=build/%.o)
HDR  := $(wildcard include/*.h) $(shell find src -name '*.h')
CFLAGS_MM := ${PETSC_CC_INCLUDES} -Iinclude -O2 -Wall
MSH  := meshes/bar80.msh meshes/bar100.msh meshes/disk.msh meshes/ball.msh meshes/block.msh meshes/box.msh
# The D2 ball at H = 0.1 (12k dofs): friction at c_p dt / h_c' = 4 (tests/test_friction_solvers.py)
MSH  += meshes/ball10.msh
# The cases with several, curved and moving obstacles (README "Cases")
MSH  += meshes/ball_bowl.msh meshes/disk_rail.msh meshes/block_push.msh meshes/ball_vgroove.msh meshes/block_squeeze.msh
# Two-body contact (issue 20): two bars end to end (non-matching and conforming interfaces), two
# balls, ball A alone (the one-ball reference against the plane x = 0, meshed exactly as in
# two_balls), a ball on a block; and the cube dropped into a V-groove
MSH  += meshes/two_bars.msh meshes/two_bars_conf.msh meshes/two_balls.msh meshes/ball_x.msh meshes/ball_block.msh
MSH  += meshes/cube_groove.msh
# Two thin rings in an oblique impact, large sliding on curved masters (issue 51): cells of 0.005 m (the
# case) and 0.01 m (its test)
MSH  += meshes/two_rings.msh meshes/two_rings_coarse.msh
# A cylinder thrown inside a held ring, 3D: large sliding on a concave master (issue 51)
MSH  += meshes/cylinder_ring.msh
# A cantilever settling on a plane under Rayleigh damping (issue 38)
MSH  += meshes/cantilever.msh
# Slender clamped cantilevers, t/L = 0.02 and 0.05, for the static start and beam theory (issue 48)
MSH  += meshes/cantilever_t02.msh meshes/cantilever_t05.msh meshes/cantilever_t05_fine.msh
# Slender cantilevers with a tip point, t/L = 0.02 on 400 x 8 and 0.05 on 160 x 8 (issue 50: large deflection)
MSH  += meshes/slender_cantilever.msh meshes/slender_cantilever_t05.msh
# A coarse cube whose whole skin is contact boundary (issue 38: the redistributed mass on coarse meshes)
MSH  += meshes/cube_drop.msh
# Bodies of their own material (README "Bodies"): a strip of two glued halves, two separate bars
MSH  += meshes/bimaterial.msh meshes/side_bars.msh
# Pressures and concentrated forces (README "Loads in time"): a square plate with Physical Points
MSH  += meshes/plate.msh
# A ball whose whole sphere is contact boundary, resting on a plane: it slides, then rolls (issue 40)
MSH  += meshes/ball_roll.msh
# A disk sliding around the inside of a circular track, svk: frames that follow the contact point (issue 40)
MSH  += meshes/disk_track.msh
# A block sliding along a longer one over many master facets (issue 40: contact pairs, large sliding)
MSH  += meshes/block_slide.msh
# A rubber block pressed on a plane by a pressure (issue 50: the static start in finite strain)
MSH  += meshes/rubber_block.msh
# Meshed rigid obstacles (issue 51, -obstacle_NAME_type mesh): a step with a rounded edge (2D lines), a
# funnel, the rounded box of options/ball_box.opts at two sizes, and the plane as segments and triangles
MSH  += meshes/step2d.msh meshes/funnel.msh meshes/box_rounded.msh meshes/box_rounded_coarse.msh meshes/plane_line.msh meshes/plane_grid.msh
# Bench meshes: the 2D D1 disk (115k dofs), the 3D D2 ball (H 0.045: 113k dofs, 3.8k contact nodes)
# and the large D2 ball of `make bench-large` (H 0.021: about 1M dofs), generated when first needed;
# the two balls of the 3d suite's two_body row at H 0.057 (116,520 dofs for both, as the D2 ball's 113k).
BALL_BENCH_H ?= 0.045
BALL_LARGE_H ?= 0.021
TWO_BALLS_BENCH_H ?= 0.057
BENCH_MSH := meshes/disk_bench.msh meshes/ball_bench.msh meshes/ball07.msh meshes/two_balls_bench.msh meshes/slab.msh

.PHONY: all deps deps-tests petsc-found meshes run check bench bench-large clean getfem-compare
all: mmcontact

deps:
	@bash scripts/install-deps
# what only the tests need besides (ParaView's pvbatch, tests/test_paraview_and_history.py)
deps-tests:
	@bash scripts/install-deps tests

petsc-found:
ifeq (${PETSC_VARIABLES},)
	@echo "PETSc not found at ${PETSC_DIR}: run 'make deps' (or 'make run', which installs it first), or set PETSC_DIR"; exit 1
endif

build/%.o: src/%.c $(HDR) | build petsc-found
	@echo "  CC  $<"
	@mkdir -p $(dir $@)
	@${PCC} ${PCC_FLAGS} ${CFLAGS_MM} -c $< -o $@
build:
	@mkdir -p build

# MUMPS with SCOTCH's nested dissection (docs/scaling.md, "Libraries: BLAS, threads and the MUMPS ordering").
# Debian builds MUMPS 5.5 twice with one ABI: libdmumps, with the PORD ordering only, which PETSc
# links, and libdmumps_ptscotch, with SCOTCH and PT-SCOTCH (package libmumps-ptscotch-5.5). Linked
# ahead of PETSc, the second's dmumps_c is the one PETSc's MUMPS interface calls, and MUMPS's automatic
# ordering picks SCOTCH: on the 113k-dof D2 ball 28% fewer flops in K~'s factorization than PORD.
# --no-as-needed keeps the libraries though nothing of ours calls them; the progress header names
# the ordering MUMPS used (INFOG(7)), and a test checks that it is SCOTCH. Only for a PETSc that
# links Debian's MUMPS 5.5 (the same ABI): another PETSc keeps the MUMPS it was built with.
PETSC_DEBIAN_MUMPS := $(shell ldd ${PETSC_DIR}/lib/libpetsc*.so 2>/dev/null | grep -q 'libdmumps-5\.5\.so' && echo yes)
ifeq (${PETSC_DEBIAN_MUMPS},yes)
MUMPS_SCOTCH_LIB ?= -Wl,--no-as-needed -l:libdmumps_ptscotch-5.5.so -l:libmumps_common_ptscotch-5.5.so -Wl,--as-needed
MUMPS_SCOTCH_CHECK := /sbin/ldconfig -p | grep -q 'libdmumps_ptscotch-5\.5\.so ' || { echo "MUMPS with SCOTCH (Debian package libmumps-ptscotch-5.5) is not installed: run 'make deps'"; exit 1; }
else
MUMPS_SCOTCH_CHECK := true
endif

mmcontact: $(OBJ)
	@${MUMPS_SCOTCH_CHECK}
	@echo "  LD  $@"
	@${CLINKER} -o $@ $(OBJ) ${MUMPS_SCOTCH_LIB} ${PETSC_LIB} -lmetis

meshes: $(MSH)
meshes/bar80.msh: meshes/bar.geo
	gmsh -2 $< -setnumber N 80 -o $@ -v 2
meshes/bar100.msh: meshes/bar.geo
	gmsh -2 $< -setnumber N 100 -o $@ -v 2
meshes/disk.msh: meshes/disk.geo
	gmsh -2 $< -o $@ -v 2
meshes/block.msh: meshes/block.geo
	gmsh -2 $< -o $@ -v 2
meshes/block_slide.msh: meshes/block_slide.geo
	gmsh -2 $< -o $@ -v 2
meshes/rubber_block.msh: meshes/rubber_block.geo
	gmsh -2 $< -o $@ -v 2
meshes/box.msh: meshes/box.geo
	gmsh -3 $< -o $@ -v 2
meshes/ball.msh: meshes/ball.geo
	gmsh -3 $< -o $@ -v 2
meshes/ball10.msh: meshes/ball.geo
	gmsh -3 $< -setnumber H 0.1 -o $@ -v 2
meshes/ball_bowl.msh: meshes/ball_bowl.geo
	gmsh -3 $< -o $@ -v 2
meshes/ball_roll.msh: meshes/ball_roll.geo
	gmsh -3 $< -o $@ -v 2
meshes/disk_rail.msh: meshes/disk_rail.geo
	gmsh -2 $< -o $@ -v 2
meshes/disk_track.msh: meshes/disk_rail.geo
	gmsh -2 $< -setnumber R 0.25 -setnumber G 0 -setnumber H 0.04 -o $@ -v 2
meshes/block_push.msh: meshes/block_push.geo
	gmsh -2 $< -o $@ -v 2
meshes/ball_vgroove.msh: meshes/ball.geo
	gmsh -3 $< -setnumber G 0.45 -o $@ -v 2
meshes/block_squeeze.msh: meshes/block_squeeze.geo
	gmsh -2 $< -o $@ -v 2
meshes/two_bars.msh: meshes/two_bars.geo
	gmsh -2 $< -o $@ -v 2
meshes/two_bars_conf.msh: meshes/two_bars.geo
	gmsh -2 $< -setnumber CONF 1 -o $@ -v 2
# H 0.18: the two-ball contact time and peak force are within 1.4% of the one ball's against the plane
meshes/two_balls.msh: meshes/two_balls.geo
	gmsh -3 $< -setnumber H 0.18 -o $@ -v 2
meshes/two_rings.msh: meshes/two_rings.geo
	gmsh -2 $< -o $@ -v 2
meshes/two_rings_coarse.msh: meshes/two_rings.geo
	gmsh -2 $< -setnumber H 0.01 -o $@ -v 2
meshes/cylinder_ring.msh: meshes/cylinder_ring.geo
	gmsh -3 $< -o $@ -v 2
meshes/ball_x.msh: meshes/two_balls.geo
	gmsh -3 $< -setnumber H 0.18 -setnumber ONLY_A 1 -o $@ -v 2
meshes/ball_block.msh: meshes/ball_block.geo
	gmsh -3 $< -o $@ -v 2
meshes/cantilever.msh: meshes/cantilever.geo
	gmsh -2 $< -o $@ -v 2
meshes/cantilever_t02.msh: meshes/cantilever.geo
	gmsh -2 $< -setnumber H 0.02 -setnumber NX 200 -setnumber NY 4 -o $@ -v 2
meshes/cantilever_t05.msh: meshes/cantilever.geo
	gmsh -2 $< -setnumber H 0.05 -setnumber NX 80 -setnumber NY 4 -o $@ -v 2
meshes/cantilever_t05_fine.msh: meshes/cantilever.geo
	gmsh -2 $< -setnumber H 0.05 -setnumber NX 160 -setnumber NY 8 -o $@ -v 2
meshes/slender_cantilever.msh: meshes/slender_cantilever.geo
	gmsh -2 $< -o $@ -v 2
meshes/slender_cantilever_t05.msh: meshes/slender_cantilever.geo
	gmsh -2 $< -setnumber H 0.05 -setnumber NX 160 -o $@ -v 2
meshes/cube_groove.msh: meshes/cube_groove.geo
	gmsh -3 $< -o $@ -v 2
meshes/cube_drop.msh: meshes/cube_drop.geo
	gmsh -3 $< -o $@ -v 2
meshes/step2d.msh: meshes/step2d.geo
	gmsh -1 $< -o $@ -v 2
meshes/plane_line.msh: meshes/plane_line.geo
	gmsh -1 $< -o $@ -v 2
meshes/funnel.msh: meshes/funnel.geo
	gmsh -2 $< -o $@ -v 2
meshes/plane_grid.msh: meshes/plane_grid.geo
	gmsh -2 $< -o $@ -v 2
meshes/box_rounded.msh: meshes/box_rounded.geo
	gmsh -2 $< -o $@ -v 2
meshes/box_rounded_coarse.msh: meshes/box_rounded.geo
	gmsh -2 $< -setnumber H 0.2 -o $@ -v 2
meshes/bimaterial.msh: meshes/bimaterial.geo
	gmsh -2 $< -o $@ -v 2
meshes/plate.msh: meshes/plate.geo
	gmsh -2 $< -o $@ -v 2
meshes/side_bars.msh: meshes/side_bars.geo
	gmsh -2 $< -o $@ -v 2
meshes/disk_bench.msh: meshes/disk.geo
	gmsh -2 $< -setnumber H 0.008 -setnumber G 0.001 -o $@ -v 2
meshes/ball_bench.msh: meshes/ball.geo
	gmsh -3 $< -setnumber H $(BALL_BENCH_H) -o $@ -v 2
meshes/two_balls_bench.msh: meshes/two_balls.geo
	gmsh -3 $< -setnumber H $(TWO_BALLS_BENCH_H) -o $@ -v 2
meshes/ball07.msh: meshes/ball.geo
	gmsh -3 $< -setnumber H 0.07 -o $@ -v 2
# auto's cost model's disks (scripts/cost_model_collect.py makes them when first needed)
meshes/disk05.msh: meshes/disk.geo
	gmsh -2 $< -setnumber H 0.05 -o $@ -v 2
meshes/disk0125.msh: meshes/disk.geo
	gmsh -2 $< -setnumber H 0.0125 -o $@ -v 2
# The surface suite's slab: 144 x 144 x 5 hexahedra split into tetrahedra, 315k dofs, 21,025 base nodes
meshes/slab.msh: meshes/slab.geo
	gmsh -3 $< -o $@ -v 2
meshes/ball_large.msh: meshes/ball.geo
	gmsh -3 $< -setnumber H $(BALL_LARGE_H) -o $@ -v 2

run: deps
	$(MAKE) mmcontact meshes
	$(MM_MPIEXEC) -n $(NP) ./mmcontact -options_file options/d1_friction.opts
	$(MM_PYTHON) scripts/plot_history.py output/d1_friction/history.csv
	$(MM_PYTHON) scripts/plot_contact.py output/d1_friction
	@echo "Open output/d1_friction/solution.xmf in ParaView; history in output/d1_friction/history.csv, plotted in output/d1_friction/history.png; contact pressure map in output/d1_friction/contact_pressure.png"

check: deps-tests
	$(MAKE) mmcontact meshes
	$(MM_PYTHON) -m pytest -q tests

# STREAM triad on 1 and 2 processes: the memory-bandwidth ceiling of the 2-rank speed-up (bench.py)
build/stream: scripts/stream.c | build petsc-found
	@echo "  CC  $<"
	@${PCC} ${PCC_FLAGS} -O2 $< -o $@

bench: deps
	$(MAKE) mmcontact meshes build/stream $(BENCH_MSH)
	$(MM_PYTHON) scripts/bench.py

# mmcontact against GetFEM on the same mesh, whole processes (issue 41): H 0.07, mu 0.2, dt 4e-3, to t = 0.08
getfem-compare: deps
	bash scripts/getfem_compare.sh

bench-large: deps
	$(MAKE) mmcontact build/stream meshes/ball_large.msh
	$(MM_PYTHON) scripts/bench.py large

clean:
	rm -rf build mmcontact meshes/*.msh output bench tests/__pycache__ .pytest_cache
