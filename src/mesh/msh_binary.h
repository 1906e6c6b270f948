/* Private to mesh: one value of a binary .msh (gmsh -bin), read by src/mesh/mesh_file.c (the nodes) and
 * src/mesh/point_groups.c (the point elements): a 4-byte int, or a size_t of the file's data size (8),
 * in this machine's byte order. */
#pragma once
#include <stdint.h>
#include <stdio.h>

/* 1 when read, 0 at the end of the file */
static inline int MMMshBinaryLong(FILE *f, size_t bytes, long *v)
{
  int32_t  i4;
  uint64_t u8;

  if (bytes == 4) {
    if (fread(&i4, 4, 1, f) != 1) return 0;
    *v = i4;
  } else {
    if (fread(&u8, 8, 1, f) != 1) return 0;
    *v = (long)u8;
  }
  return 1;
}
