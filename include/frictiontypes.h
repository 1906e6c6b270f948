/* The friction component (src/friction/). */
#pragma once
#include "mmbase.h"

/* The Coulomb friction solver: an opaque handle, owned by the friction component (include/friction.h,
 * src/friction/). */
typedef struct _p_MMFriction *MMFriction;
