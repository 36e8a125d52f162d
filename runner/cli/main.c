#include "runner/cli/cli.h"
#include "runner/folder/folder.h"
#include "runner/trial/provenance.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include "common/fsutil.h"

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

/* A command's output that did not reach its file is a failure like any other: stdio
 * keeps a failed write as the stream's error flag only, so both streams are flushed and
 * checked where every command returns (stdout on a full disk gave truncated JSON and
 * status 0). A failure with stdout is said on stderr; one with stderr cannot be said. */
static int check_std_streams(const char *cmd, int rc)
{
    errno = 0;
    bool out_failed = fflush(stdout) != 0 || ferror(stdout);
    int e = errno;
    if (out_failed) {
        char msg[256] = "standard output: a write failed (the output is incomplete)";
        if (e)   /* the last write's cause; an earlier failure's errno is gone */
            fs_error_message(msg, sizeof msg, "standard output", e);
        fprintf(stderr, "shadesweep%s%s: %s\n", cmd ? " " : "", cmd ? cmd : "", msg);
    }
    bool err_failed = fflush(stderr) != 0 || ferror(stderr);
    return (out_failed || err_failed) && rc < 2 ? 2 : rc;
}

int main(int argc, char **argv)
{
    folder_std_fds();   /* a closed stderr must not become the first file opened */
    /* Not on a terminal, stdout is written in 1 MiB blocks rather than 4 KiB: a write
     * that fails then fails in check_std_streams' flush, whose errno names the cause (a
     * failure inside a command's printf leaves only the stream's error flag). */
    static char out_buf[1 << 20];   /* glibc ignores the size of a buffer it allocates */
    if (!isatty(STDOUT_FILENO))
        setvbuf(stdout, out_buf, _IOFBF, sizeof out_buf);
    allocator_fixed();
    /* Past a file-size limit (ulimit -f) write(2) then fails with EFBIG, and the file's
     * writer names it (failed:write, its temporary removed); the default action killed
     * the sweep silently, leaving the temporary. Ignored also in the run children. */
    signal(SIGXFSZ, SIG_IGN);
    provenance_set_command(argc, argv);
    return check_std_streams(argc > 1 ? argv[1] : NULL, cli_main(argc, argv));
}
