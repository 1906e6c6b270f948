/* The run's context, MMCtx (src/app/): the problem as the user gave it, and each component's object or
 * data, created, set up and destroyed by main.c. Only src/app/ includes this header. */
#pragma once
#include "mmbase.h"
#include "apptypes.h"
#include "obstacle.h"
#include "fem.h"
#include "contact.h"
#include "friction.h"
#include "ts.h"
#include "io.h"

typedef struct _MMCtx {
  MMOptions   opt;
  MMIOProblem iopb; /* the part of opt the output, checkpoint and progress read (MMOptionsGetIOProblem) */
  MMMaterial  material;
  MMOperators op;
  MMLoads     loads;
  MMContact   contact;
  MMFriction  friction;
  MMNewmark   nm; /* the stepper (src/ts/): its state, history and damping through MMNewmarkGet* */
  MMProgress  progress;
  MMOutput    out;
  MMCheckpoint ckpt;
} MMCtx;
