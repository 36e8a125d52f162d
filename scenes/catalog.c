/* The named scenes manifests can ask for. scene.c builds them. */
#include "scenes/scene.h"

#include <stdlib.h>
#include <string.h>

static const scene_catalog_entry catalog[] = {
    {"empty", "no geometry: an orbiting camera and the run's lights; measures the harness"},
    {"shapes", "a floor and a 3 x 3 grid of textured, glossy, normal-mapped and emissive "
               "objects, two of them rotating, under an orbiting camera"},
};

/* Scenes that fail on purpose at schedule time 0.2 s, for the tests of run
 * isolation; they exist only where SHADESWEEP_TEST_SCENES=1. */
static const scene_catalog_entry test_catalog[] = {
    {"test-abort", "calls abort()"},
    {"test-segv", "raises SIGSEGV"},
    {"test-sigkill", "raises SIGKILL, as the kernel's OOM killer would"},
    {"test-hang", "never returns"},
};

static bool test_scenes_enabled(void)
{
    const char *v = getenv("SHADESWEEP_TEST_SCENES");
    return v && strcmp(v, "1") == 0;
}

size_t scene_catalog_count(void)
{
    return sizeof catalog / sizeof catalog[0] +
           (test_scenes_enabled() ? sizeof test_catalog / sizeof test_catalog[0] : 0);
}

const scene_catalog_entry *scene_catalog_at(size_t i)
{
    size_t n = sizeof catalog / sizeof catalog[0];
    if (i < n)
        return &catalog[i];
    return i < scene_catalog_count() ? &test_catalog[i - n] : NULL;
}

const scene_catalog_entry *scene_catalog_find(const char *name)
{
    for (size_t i = 0; i < scene_catalog_count(); i++)
        if (strcmp(scene_catalog_at(i)->name, name) == 0)
            return scene_catalog_at(i);
    return NULL;
}
