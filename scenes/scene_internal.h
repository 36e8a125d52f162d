#pragma once
/* What scenes/scene_make.c shares with the other pieces of scene construction; not part of
 * the scenes interface (nothing outside scenes/ includes it). */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "scenes/scene.h"

/* Triangle t (indices 3t..3t+2 of its mesh) of object o as it stands at schedule time 0
 * (scene_place.c): its world corners w, its area normal n (length twice the area, towards
 * the counter-clockwise front face), and its area (0 when not finite). */
double scene_triangle_at_0(const scene *s, const scene_object *o, uint32_t t, sm_vec3 w[3],
                           sm_vec3 n);

/* The run's lights on a built scene (scene_place.c): the authored ones (placement scene)
 * or placed from lp. With `check`, only whether they can be: the same failures and
 * messages, but no light is placed and s->lights is left NULL (what a plan check asks of
 * many runs). */
bool scene_place_lights(scene *s, const scene_light *authored, uint32_t nauthored,
                        uint32_t ncoverage, const light_params *lp, bool check, char *err,
                        size_t errlen);

/* FNV-1a 64, the same function as runner/manifest/hash.h (scenes/ cannot reach runner/), continued
 * from h (start: 0xcbf29ce484222325). */
uint64_t scene_fnv1a64_more(uint64_t h, const void *data, size_t len);
/* CLOCK_MONOTONIC in seconds: the load's and the cache's times (scene_file_times). */
double scene_now_s(void);
/* One file's step of a file scene's content hash (scene_file_info.hash): its length as 8
 * little-endian bytes, then its bytes. */
uint64_t scene_file_hash_more(uint64_t h, const void *data, size_t len);

/* The scene cache's two ends (scene_cache.c) for scene_build_cache: the cached scene as a
 * builder holding it and its authored lights (c freed; NULL with a message out of
 * memory), and a built scene stored as to says (to->written or to->note). */
struct scene_builder;
struct scene_builder *scene_cached_take(scene_cached *c, char *err, size_t errlen);
void scene_cache_write(scene_cache_store *to, const struct scene_builder *b);
