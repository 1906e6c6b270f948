/* app's own log stages and events (src/app/app_log.c): the set-up and the time loop, and each phase
 * of the set-up (main.c's MMPhase), so that -log_view accounts for all of it. */
#pragma once
#include "mmbase.h"

typedef struct {
  PetscLogStage setup, solve;
  PetscLogEvent mesh_load, fe_setup, contact_setup, loads_setup, initial_state, friction_setup, step_matrix, energy_initial, deformation_check, output_open;
} MMAppLog;
PETSC_INTERN MMAppLog       MMAppEvents;
PETSC_INTERN PetscErrorCode MMAppInitializePackage(void);
