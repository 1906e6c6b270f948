/* Logging events (src/sys/log.c). */
#pragma once
#include "mmbase.h"

typedef struct {
  PetscLogEvent energy, momenta;
} MMLog;
