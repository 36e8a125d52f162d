/* The named scenes manifests can ask for. scene.c builds them. */
#include "scenes/scene.h"

#include <string.h>

static const scene_catalog_entry catalog[] = {
    {"empty", "no geometry: an orbiting camera and the run's lights; measures the harness"},
};

size_t scene_catalog_count(void) { return sizeof catalog / sizeof catalog[0]; }

const scene_catalog_entry *scene_catalog_at(size_t i)
{
    return i < scene_catalog_count() ? &catalog[i] : NULL;
}

const scene_catalog_entry *scene_catalog_find(const char *name)
{
    for (size_t i = 0; i < scene_catalog_count(); i++)
        if (strcmp(catalog[i].name, name) == 0)
            return &catalog[i];
    return NULL;
}
