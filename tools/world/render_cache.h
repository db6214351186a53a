/*
 * tools/world/render_cache.h - on-disk cache of rendered frames, on only
 * when FIELDLOC_RENDER_CACHE names a directory (render_cache.c says why
 * and how).  render_frame uses it; nothing else needs to.
 */
#ifndef FIELDLOC_TOOLS_RENDER_CACHE_H
#define FIELDLOC_TOOLS_RENDER_CACHE_H

#include "world/render.h"

/* 0 and *out filled (free with render_frame_free) when the cache is on and
 * holds this scene's frame; -1 (and *out zeroed) otherwise. */
int render_cache_load(const render_scene_t *sc, render_frame_t *out);

/* Store a frame rendered from sc (nothing when the cache is off; a write
 * error leaves no file). */
void render_cache_store(const render_scene_t *sc, const render_frame_t *fr);

/* The scene's file in the cache (0), or -1 when the cache is off (for
 * tests: no directory listing, which qemu-user cannot always do). */
int render_cache_file(const render_scene_t *sc, char *path, size_t cap);

#endif
