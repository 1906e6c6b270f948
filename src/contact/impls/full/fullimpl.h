/* Private to the full formulation (src/contact/impls/full/). */
#pragma once
#include "../../contactimpl.h"

/* The full formulation's state (MMContact's data): the VI on all dofs, prefix contact_ */
typedef struct {
  SNES snes;
} MMContact_Full;

static inline MMContact_Full *MMFullData(MMContact ct)
{
  return (MMContact_Full *)ct->data;
}
