/* The exit statuses and error codes: in sys.h, the one public header of src/sys/ */
#pragma once
#include "sys.h"
