/* Logging events (src/sys/log.c). */
#pragma once
#include "mmbase.h"

typedef struct {
  PetscLogStage setup, solve, output;
  PetscLogEvent assemble, contact_solve, contact_recover, friction, energy, momenta, checkpoint;
  PetscLogEvent restart_output; /* -restart: the history cut and the earlier snapshots copied */
  PetscLogEvent candidate_columns, candidate_operator; /* K~^{-1} E columns of new candidates; the set's dense block */
  PetscLogEvent kt_reuse;        /* the kept factor of K~ for the previous dt taken back: no factorization */
  PetscLogEvent kt_setup, kt_solve, as_iterate, as_linear; /* K~ PC set-up and solves; active-set iterations and their CG */
  /* the set-up's phases, one event each (src/app/main.c), so that -log_view accounts for all of it */
  PetscLogEvent mesh_load, fe_setup, contact_setup, loads_setup, initial_state, friction_setup, step_matrix, energy_initial, deformation_check, output_open;
} MMLog;
