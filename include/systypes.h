/* Logging events (src/sys/log.c). */
#pragma once
#include "mmbase.h"

typedef struct {
  PetscLogEvent assemble, contact_solve, contact_recover, friction, energy, momenta;
  PetscLogEvent candidate_columns, candidate_operator; /* K~^{-1} E columns of new candidates; the set's dense block */
  PetscLogEvent kt_reuse;        /* the kept factor of K~ for the previous dt taken back: no factorization */
  PetscLogEvent kt_setup, kt_solve, as_iterate, as_linear; /* K~ PC set-up and solves; active-set iterations and their CG */
} MMLog;
