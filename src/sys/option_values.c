/* Option readers that check the value before PETSc parses it, shared by every component's
 * SetFromOptions: PETSc's own message for "-E 1e3Pa" names the string, not the option, and an option
 * given without a value ("-E" followed by another option, or last) silently keeps its default, even
 * over the options file's value. */
#include <errno.h>
#include <stdlib.h>
#include <strings.h> /* strcasecmp */
#include "sys.h"

/* Whether text (up to len characters) is one number of the kind, all of it. */
static PetscBool IsNumber(const char text[], size_t len, MMValueKind kind)
{
  char  buf[128], *end;
  char *p;

  if (!len || len >= sizeof(buf)) return PETSC_FALSE;
  memcpy(buf, text, len);
  buf[len] = 0;
  for (p = buf; *p == ' '; ++p) {}
  errno = 0;
  if (kind == MM_VALUE_INT) (void)strtoll(p, &end, 10);
  else (void)strtod(p, &end);
  while (*end == ' ') ++end;
  return (PetscBool)(end != p && !*end);
}

/* Whether an integer's text (up to len characters) fits a PetscInt: PETSc's own parser wraps a value
 * beyond it silently (-ts_max_steps 3000000000 became -1294967296). */
static PetscBool FitsInt(const char text[], size_t len)
{
  char      buf[128];
  long long n;

  if (!len || len >= sizeof(buf)) return PETSC_FALSE;
  memcpy(buf, text, len);
  buf[len] = 0;
  errno = 0;
  n     = strtoll(buf, NULL, 10);
  return (PetscBool)(errno != ERANGE && n <= PETSC_MAX_INT && n >= PETSC_MIN_INT);
}

/*@
  MMOptionsCheckValue - Refuses an option given without a value, or whose value is not numbers of
  the kind, before PETSc parses it

  Collective on comm

  Input Parameters:
+ comm - the communicator a refusal is raised on
. name - the option's full name
- kind - MM_VALUE_REAL, MM_VALUE_INT or MM_VALUE_TEXT

  Note:
  Nothing is checked when the option is not given. A value of MM_VALUE_INT or MM_VALUE_REAL may be a
  comma-separated list; each entry must be one number, all of it (no unit: 1e3, not 1e3Pa), and an
  integer must fit a PetscInt. MM_VALUE_TEXT only needs a value: an empty text is left to the
  option's own check.

  PETSc's own message for "-E 1e3Pa" names the string, not the option, and an option given without a
  value silently keeps its default, even over the options file's value.

  Level: developer

.seealso: `MMOptionsCheckFinite()`, `MMOptionsReal()`, `MMOptionsInt()`
@*/
PetscErrorCode MMOptionsCheckValue(MPI_Comm comm, const char name[], MMValueKind kind)
{
  const char *value;
  PetscBool   set;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsFindPair(NULL, NULL, name, &value, &set));
  if (!set) PetscFunctionReturn(0);
  PetscCheck(value, comm, PETSC_ERR_USER_INPUT, "%s was given without a value: write \"%s VALUE\", or leave the option out for its default", name, name);
  /* an empty text ("") is for the option's own check to name: -output_dir "" is refused there */
  if (kind == MM_VALUE_TEXT) PetscFunctionReturn(0);
  PetscCheck(value[0], comm, PETSC_ERR_USER_INPUT, "%s is given an empty value: give %s", name, kind == MM_VALUE_INT ? "an integer" : "a number");
  for (const char *p = value; p;) {
    const char  *comma = strchr(p, ',');
    const size_t len   = comma ? (size_t)(comma - p) : strlen(p);
    PetscCheck(IsNumber(p, len, kind), comm, PETSC_ERR_USER_INPUT, "%s %s: \"%.*s\" is not %s. Give %s%s", name, value, (int)len, p, kind == MM_VALUE_INT ? "an integer" : "a number", kind == MM_VALUE_INT ? "whole numbers" : "plain numbers, in SI units, without a unit (1e3, not 1e3Pa)", strchr(value, ',') ? ", separated by commas without blanks" : "");
    PetscCheck(kind != MM_VALUE_INT || FitsInt(p, len), comm, PETSC_ERR_USER_INPUT, "%s %.*s is beyond the integers a run can count (%lld to %lld)", name, (int)len, p, (long long)PETSC_MIN_INT, (long long)PETSC_MAX_INT);
    p = comma ? comma + 1 : NULL;
  }
  PetscFunctionReturn(0);
}

/*@
  MMOptionsCheckFinite - Refuses a real option's values unless every one is finite

  Collective on comm

  Input Parameters:
+ comm - the communicator a refusal is raised on
. name - the option's name, for the message
. v    - the values
- n    - how many

  Note:
  PETSc parses "nan" and "inf" as numbers: every real option is checked here, by name.

  Level: developer

.seealso: `MMOptionsCheckValue()`, `MMOptionsReal()`, `MMOptionsRealArray()`
@*/
PetscErrorCode MMOptionsCheckFinite(MPI_Comm comm, const char name[], const PetscReal v[], PetscInt n)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; ++i) PetscCheck(!PetscIsInfOrNanReal(v[i]), comm, PETSC_ERR_USER_INPUT, "%s: entry %" PetscInt_FMT " is %s; every value must be a finite number", name, i, PetscIsNanReal(v[i]) ? "NaN" : "infinite");
  PetscFunctionReturn(0);
}

/* The full name of option name in the block's options prefix (PetscOptionsBegin's prefix, as an
 * object's -PREFIX_name): the name the checks look up and their messages quote. */
static const char *FullName(PetscOptionItems *PetscOptionsObject, const char name[], char full[], size_t len)
{
  if (!PetscOptionsObject || !PetscOptionsObject->prefix || name[0] != '-') return name;
  snprintf(full, len, "-%s%s", PetscOptionsObject->prefix, name + 1);
  return full;
}

/*@
  MMOptionsReal - Reads a real option, its value checked first and refused unless finite

  Collective on comm

  Input Parameters:
+ PetscOptionsObject - the PetscOptionsBegin() block's options object (its prefix)
. comm               - the communicator a refusal is raised on
. name               - the option's name, without the block's prefix
- help               - its help text

  Output Parameter:
. v - the value; on input, the default

  Level: intermediate

.seealso: `MMOptionsRealArray()`, `MMOptionsCheckValue()`, `MMOptionsCheckFinite()`
@*/
PetscErrorCode MMOptionsReal(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], PetscReal *v)
{
  char        fullbuf[PETSC_MAX_OPTION_NAME];
  const char *full = FullName(PetscOptionsObject, name, fullbuf, sizeof(fullbuf));
  PetscFunctionBeginUser;
  PetscCall(MMOptionsCheckValue(comm, full, MM_VALUE_REAL));
  PetscCall(PetscOptionsReal(name, help, NULL, *v, v, NULL));
  PetscCall(MMOptionsCheckFinite(comm, full, v, 1));
  PetscFunctionReturn(0);
}

/*@
  MMOptionsRealArray - Reads a real array option of at most nmax finite entries

  Collective on comm

  Input Parameters:
+ PetscOptionsObject - the PetscOptionsBegin() block's options object (its prefix)
. comm               - the communicator a refusal is raised on
. name               - the option's name, without the block's prefix
. help               - its help text
- nmax               - the most entries allowed, at most MM_MAX_DIM * MM_MAX_DIM

  Output Parameters:
+ v     - the nmax values: on input the defaults; when the option is given, its entries and zeros
          after them
- count - how many entries were given, -1 if the option was not

  Note:
  A real array option of at most nmax finite entries; *count is how many were given, -1 if none. One
  slot more is read, so that too many entries are refused rather than cut off.

  Level: intermediate

.seealso: `MMOptionsReal()`, `MMOptionsCheckValue()`, `MMOptionsCheckFinite()`
@*/
PetscErrorCode MMOptionsRealArray(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], PetscInt nmax, PetscReal v[], PetscInt *count)
{
  char        fullbuf[PETSC_MAX_OPTION_NAME];
  const char *full = FullName(PetscOptionsObject, name, fullbuf, sizeof(fullbuf));
  PetscReal buf[MM_MAX_DIM * MM_MAX_DIM + 1];
  PetscInt  n = nmax + 1;
  PetscBool set;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < nmax; ++i) buf[i] = v[i];
  PetscCall(MMOptionsCheckValue(comm, full, MM_VALUE_REAL));
  PetscCall(PetscOptionsRealArray(name, help, NULL, buf, &n, &set));
  *count = set ? n : -1;
  if (!set) PetscFunctionReturn(0);
  PetscCheck(n <= nmax, comm, PETSC_ERR_USER_INPUT, "%s has more than %" PetscInt_FMT " entries", full, nmax);
  PetscCall(MMOptionsCheckFinite(comm, full, buf, n));
  for (PetscInt i = 0; i < nmax; ++i) v[i] = i < n ? buf[i] : 0;
  PetscFunctionReturn(0);
}

/*@
  MMOptionsInt - Reads an integer option, its value checked first (a whole number that fits a
  PetscInt)

  Collective on comm

  Input Parameters:
+ PetscOptionsObject - the PetscOptionsBegin() block's options object (its prefix)
. comm               - the communicator a refusal is raised on
. name               - the option's name, without the block's prefix
- help               - its help text

  Output Parameter:
. v - the value; on input, the default

  Level: intermediate

.seealso: `MMOptionsReal()`, `MMOptionsCheckValue()`
@*/
PetscErrorCode MMOptionsInt(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], PetscInt *v)
{
  char        fullbuf[PETSC_MAX_OPTION_NAME];
  const char *full = FullName(PetscOptionsObject, name, fullbuf, sizeof(fullbuf));
  PetscFunctionBeginUser;
  PetscCall(MMOptionsCheckValue(comm, full, MM_VALUE_INT));
  PetscCall(PetscOptionsInt(name, help, NULL, *v, v, NULL));
  PetscFunctionReturn(0);
}

/*@
  MMOptionsBool - Reads a switch: on when given alone, else its value must be one PETSc reads as a
  logical

  Collective on comm

  Input Parameters:
+ PetscOptionsObject - the PetscOptionsBegin() block's options object (its prefix)
. comm               - the communicator a refusal is raised on
. name               - the option's name, without the block's prefix
- help               - its help text

  Output Parameter:
. v - the value; on input, the default

  Note:
  The values taken are 1, 0, true, false, yes, no, on and off, in any case; PETSc's own error for
  another does not name the option.

  Level: intermediate

.seealso: `MMOptionsEnum()`, `MMOptionsString()`
@*/
PetscErrorCode MMOptionsBool(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], PetscBool *v)
{
  char        fullbuf[PETSC_MAX_OPTION_NAME];
  const char *full = FullName(PetscOptionsObject, name, fullbuf, sizeof(fullbuf));
  static const char *const words[] = {"1", "0", "true", "false", "yes", "no", "on", "off"};
  const char              *value;
  PetscBool                set, known = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsFindPair(NULL, NULL, full, &value, &set));
  for (size_t i = 0; set && value && value[0] && i < PETSC_STATIC_ARRAY_LENGTH(words); ++i) known = (PetscBool)(known || !strcasecmp(value, words[i]));
  PetscCheck(!set || !value || !value[0] || known, comm, PETSC_ERR_USER_INPUT, "%s %s: give 1 or 0 (also true/false, yes/no, on/off), or %s alone for 1", full, value, full);
  PetscCall(PetscOptionsBool(name, help, NULL, *v, v, NULL));
  PetscFunctionReturn(0);
}

/*@
  MMOptionsString - Reads a text option (a name, a list of names, a path), refused when given
  without a value

  Collective on comm

  Input Parameters:
+ PetscOptionsObject - the PetscOptionsBegin() block's options object (its prefix)
. comm               - the communicator a refusal is raised on
. name               - the option's name, without the block's prefix
. help               - its help text
- len                - the size of v

  Output Parameters:
+ v   - the value; on input, the default
- set - whether the option was given

  Level: intermediate

.seealso: `MMOptionsSplitNames()`, `MMOptionsEnum()`
@*/
PetscErrorCode MMOptionsString(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], char v[], size_t len, PetscBool *set)
{
  char        fullbuf[PETSC_MAX_OPTION_NAME];
  const char *full = FullName(PetscOptionsObject, name, fullbuf, sizeof(fullbuf));
  PetscFunctionBeginUser;
  PetscCall(MMOptionsCheckValue(comm, full, MM_VALUE_TEXT));
  PetscCall(PetscOptionsString(name, help, NULL, v, v, len, set));
  PetscFunctionReturn(0);
}

/* The valid values of a PETSc enum list (names, then the type name, the prefix and a NULL), as
 * "a, b or c" into buf. */
static PetscInt EnumNames(const char *const list[])
{
  PetscInt n = 0;

  while (list[n]) ++n;
  return n - 2; /* the names are followed by the enum's type name and its prefix (then NULL) */
}

static void EnumChoices(const char *const list[], char buf[], size_t len)
{
  const PetscInt n = EnumNames(list);

  buf[0] = 0;
  for (PetscInt i = 0; i < n; ++i) {
    size_t used = strlen(buf);
    snprintf(buf + used, len - used, "%s%s", i == 0 ? "" : (i == n - 1 ? " or " : ", "), list[i]);
  }
}

/*@
  MMOptionsEnum - Reads an enumerated option, its value refused by option name unless it is one of
  the list's

  Collective on comm

  Input Parameters:
+ PetscOptionsObject - the PetscOptionsBegin() block's options object (its prefix)
. comm               - the communicator a refusal is raised on
. name               - the option's name, without the block's prefix
. help               - its help text
- list               - the PETSc enum list: the names, the type name, the prefix and NULL

  Output Parameter:
. v - the value; on input, the default

  Note:
  The value is matched without regard to case; the refusal lists the valid values.

  An enumerated option. The value is checked here, by option name, because PETSc's own refusal
  (PETSC_ERR_USER) is not an input error to the exit statuses: a trace and status 83, where every
  other refused option gives one line and 64 (docs/developer.md, "Exit statuses").

  Level: intermediate

.seealso: `MMOptionsBool()`, `MMOptionsString()`
@*/
PetscErrorCode MMOptionsEnum(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char name[], const char help[], const char *const list[], PetscEnum *v)
{
  char        fullbuf[PETSC_MAX_OPTION_NAME];
  const char *full = FullName(PetscOptionsObject, name, fullbuf, sizeof(fullbuf));
  const char *value;
  PetscBool   set, known = PETSC_FALSE;
  char        choices[512];

  PetscFunctionBeginUser;
  PetscCall(MMOptionsCheckValue(comm, full, MM_VALUE_TEXT));
  PetscCall(PetscOptionsFindPair(NULL, NULL, full, &value, &set));
  if (set && value) {
    for (PetscInt i = 0; i < EnumNames(list); ++i) known = (PetscBool)(known || !strcasecmp(value, list[i]));
    EnumChoices(list, choices, sizeof(choices));
    PetscCheck(known, comm, PETSC_ERR_USER_INPUT, "%s %s is not a valid value: use %s", full, value, choices);
  }
  PetscCall(PetscOptionsEnum(name, help, NULL, list, *v, v, NULL));
  PetscFunctionReturn(0);
}

/*@
  MMOptionsSplitNames - Splits a comma-separated list of names into a freshly allocated array,
  refusing an empty name, a blank or a name given twice

  Collective on comm

  Input Parameters:
+ comm   - the communicator a refusal is raised on
. option - the option's name, for the messages
- list   - the list

  Output Parameters:
+ n     - how many names, 0 for an empty list
- names - the names, NULL for an empty list; free with PetscStrToArrayDestroy()

  Note:
  Splits a comma-separated list of physical names into a freshly allocated array. PetscStrToArray
  would skip an empty name ("floor,,wall"), a typo that would drop an obstacle or a boundary.

  A name given twice would make two objects of one name (two force columns, two bodies).

  Level: intermediate

.seealso: `MMOptionsString()`
@*/
PetscErrorCode MMOptionsSplitNames(MPI_Comm comm, const char option[], const char list[], PetscInt *n, char ***names)
{
  int    argc;
  size_t len = strlen(list);

  PetscFunctionBeginUser;
  *n     = 0;
  *names = NULL;
  if (!list[0]) PetscFunctionReturn(0);
  PetscCheck(list[0] != ',' && list[len - 1] != ',' && !strstr(list, ",,"), comm, PETSC_ERR_USER_INPUT, "%s %s has an empty name: give the names separated by single commas", option, list);
  for (const char *p = list; *p; ++p) PetscCheck(*p != ' ' && *p != '\t', comm, PETSC_ERR_USER_INPUT, "%s \"%s\" has a blank: give the names separated by commas, without blanks", option, list);
  PetscCall(PetscStrToArray(list, ',', &argc, names));
  *n = argc;
  /* a name given twice would make two objects of one name (two force columns, two bodies) */
  for (PetscInt b = 0; b < *n; ++b)
    for (PetscInt a = 0; a < b; ++a) {
      PetscBool same;
      PetscCall(PetscStrcmp((*names)[a], (*names)[b], &same));
      PetscCheck(!same, comm, PETSC_ERR_USER_INPUT, "%s %s names %s twice", option, list, (*names)[b]);
    }
  PetscFunctionReturn(0);
}
