/*
 * fieldloc/config.h - every compile-time capacity of the module, in one
 * place.  Each option has a default, may be overridden with -D, and is range
 * checked here.  State structs are sized from these; nothing is allocated.
 */
#ifndef FIELDLOC_CONFIG_H
#define FIELDLOC_CONFIG_H

/* Largest image width or height accepted, pixels.  Default 1280 (NAO v6
 * full resolution is 1280x960).  Range 16..4096. */
#ifndef FL_IMAGE_MAX_DIM
#define FL_IMAGE_MAX_DIM 1280
#endif
#if FL_IMAGE_MAX_DIM < 16 || FL_IMAGE_MAX_DIM > 4096
#error "FL_IMAGE_MAX_DIM must be in 16..4096"
#endif

#endif /* FIELDLOC_CONFIG_H */
