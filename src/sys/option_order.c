/* Which of two options was given later, as PETSc reads them: PETSC_OPTIONS first, then the command
 * line from left to right, an options file's lines where -options_file names it. PETSc keeps the
 * last value of each option but not the order of different ones; where one option's data replaces
 * another's (a load's _amplitude kind given after its _amplitude_time, src/app/options.c), the
 * later one wins, as a later value of the same option does. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <ctype.h>
#include "sys.h"

typedef struct {
  const char *a, *b;   /* the two option names */
  long        pa, pb;  /* the position of each one's last appearance, -1 if none */
  long        counter; /* the options seen so far */
} OptionOrder;

static void Seen(OptionOrder *o, const char *token, size_t len)
{
  if (len < 2 || token[0] != '-' || !isalpha((unsigned char)token[1])) return; /* a value such as -1 */
  ++o->counter;
  if (strlen(o->a) == len && !strncasecmp(token, o->a, len)) o->pa = o->counter;
  if (strlen(o->b) == len && !strncasecmp(token, o->b, len)) o->pb = o->counter;
}

static void ScanFile(OptionOrder *o, const char file[], int depth);

/* The tokens of text (blanks between them), with -options_file FILE followed into FILE. */
static void ScanText(OptionOrder *o, const char *text, int depth)
{
  const char *p = text;
  int         next_is_file = 0;

  while (*p) {
    const char *start;
    while (*p && isspace((unsigned char)*p)) ++p;
    if (*p == '#') { /* a comment runs to the end of its line */
      while (*p && *p != '\n') ++p;
      continue;
    }
    start = p;
    while (*p && !isspace((unsigned char)*p)) ++p;
    if (p == start) break;
    if (next_is_file) {
      char name[PETSC_MAX_PATH_LEN];
      snprintf(name, sizeof(name), "%.*s", (int)(p - start), start);
      ScanFile(o, name, depth + 1);
      next_is_file = 0;
      continue;
    }
    Seen(o, start, (size_t)(p - start));
    next_is_file = (size_t)(p - start) == 13 && !strncmp(start, "-options_file", 13);
  }
}

static void ScanFile(OptionOrder *o, const char file[], int depth)
{
  FILE *f;
  long  n;
  char *text;

  if (depth > 8 || !(f = fopen(file, "r"))) return;
  if (!fseek(f, 0, SEEK_END) && (n = ftell(f)) >= 0 && !fseek(f, 0, SEEK_SET) && (text = (char *)calloc((size_t)n + 1, 1))) {
    if (fread(text, 1, (size_t)n, f) == (size_t)n) ScanText(o, text, depth);
    free(text);
  }
  (void)fclose(f);
}

/*@
  MMOptionsOrder - Tells which of two options was given later: in PETSC_OPTIONS, on the command
  line, or in an options file in its place

  Not collective

  Input Parameters:
+ a - the first option's name
- b - the second option's name

  Output Parameter:
. order - 1 if a was given after b, -1 if before, 0 if either was not given

  Level: developer

.seealso: `MMOptionsString()`
@*/
PetscErrorCode MMOptionsOrder(const char a[], const char b[], PetscInt *order)
{
  OptionOrder o = {a, b, -1, -1, 0};
  const char *env = getenv("PETSC_OPTIONS");
  int         argc;
  char      **args;

  PetscFunctionBeginUser;
  if (env) ScanText(&o, env, 0);
  PetscCall(PetscGetArgs(&argc, &args));
  for (int i = 1; i < argc; ++i) {
    if (!strcmp(args[i], "-options_file") && i + 1 < argc) {
      ++o.counter;
      ScanFile(&o, args[++i], 1);
      continue;
    }
    Seen(&o, args[i], strlen(args[i]));
  }
  *order = o.pa < 0 || o.pb < 0 ? 0 : (o.pa > o.pb ? 1 : -1);
  PetscFunctionReturn(0);
}
