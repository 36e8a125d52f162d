#include "runner/cli.h"
#include "runner/folder.h"
#include "runner/provenance.h"

#ifdef __GLIBC__
#include <malloc.h>
#endif

/* glibc serves a large block with its own mmap and unmaps it on free, until a large
 * free raises that threshold for the rest of the process (and its trim threshold with
 * it). llvmpipe allocates and frees large blocks for every compute dispatch with
 * barriers, so each frame paid the page faults of fresh mappings until some earlier
 * free happened to move the threshold: clustered's cull took 150 ms a frame before the
 * error reference's frame (which frees large targets) and 30 ms after it, on the same
 * frames. Fixed thresholds make a frame's time independent of what the process
 * happened to free before it: blocks up to 32 MiB come from the heap, and up to
 * 256 MiB of free heap is kept rather than given back between frames. */
static void allocator_fixed(void)
{
#ifdef __GLIBC__
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

int main(int argc, char **argv)
{
    folder_std_fds();   /* a closed stderr must not become the first file opened */
    allocator_fixed();
    provenance_set_command(argc, argv);
    return cli_main(argc, argv);
}
