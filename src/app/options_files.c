/* The options files a user names, checked before PETSc reads them (README "Exit status"). */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>
#include <sys/stat.h>
#include "appimpl.h"
#include "sys.h"

/* Before PetscInitialize, which reads the options files and would stop with a traceback on their
 * first defect: a file that cannot be opened, or one that starts with a UTF-8 byte order mark (some
 * editors write one; PETSc takes it for the first option's name), or a directory. Plain C: PETSc is not up yet, so
 * the message is printed by the first rank alone (the launcher's rank variable), and every rank
 * exits with MM_EXIT_USAGE. Returns 0 when the files are fine. */
int MMOptionsCheckFiles(int argc, char **argv)
{
  const char *rank = getenv("OMPI_COMM_WORLD_RANK");
  const int   first = !rank || !strcmp(rank, "0");

  for (int i = 1; i < argc; ++i) {
    FILE         *f;
    struct stat   st;
    unsigned char head[3] = {0, 0, 0};
    const char   *name;
    size_t        n;

    if (strcmp(argv[i], "-options_file") && strcmp(argv[i], "-options_file_yaml")) continue;
    name = i + 1 < argc ? argv[i + 1] : NULL;
    if (!name || name[0] == '-' || !name[0]) {
      if (first) fprintf(stderr, "mmcontact error: %s was given without a file name: write \"%s FILE\"\n", argv[i], argv[i]);
      return MM_EXIT_USAGE;
    }
    if (!stat(name, &st) && S_ISDIR(st.st_mode)) {
      if (first) fprintf(stderr, "mmcontact error: the options file %s is a directory: name a file of options in it, e.g. %s/case.opts\n", name, name);
      return MM_EXIT_USAGE;
    }
    if (!(f = fopen(name, "rb"))) {
      if (first) fprintf(stderr, "mmcontact error: the options file %s cannot be read: %s\n", name, strerror(errno));
      return MM_EXIT_USAGE;
    }
    n = fread(head, 1, sizeof(head), f);
    fclose(f);
    if (n == 3 && head[0] == 0xEF && head[1] == 0xBB && head[2] == 0xBF) {
      if (first) fprintf(stderr, "mmcontact error: the options file %s starts with a UTF-8 byte order mark (bytes EF BB BF), which PETSc reads as part of the first option: save it as UTF-8 without a byte order mark (or plain ASCII)\n", name);
      return MM_EXIT_USAGE;
    }
  }
  return 0;
}
