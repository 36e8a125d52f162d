/* shadesweep report: the Python report (python/shadesweep_report, installed under
 * DATADIR/shadesweep/python) run by python3 with the package on PYTHONPATH.
 * The package is looked for beside the program (BINDIR/../DATADIR/...: an installed,
 * possibly relocated tree), then at the configured install path, then in the source
 * tree the program was built from; SHADESWEEP_PYDIR overrides all three. The
 * interpreter is SHADESWEEP_PYTHON, else /usr/bin/python3, else python3 on PATH. */
#include "runner/answer/commands.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "config.h"

static bool has_package(const char *dir)
{
    char p[4200];
    struct stat st;
    snprintf(p, sizeof p, "%s/shadesweep_report/__main__.py", dir);
    return stat(p, &st) == 0 && S_ISREG(st.st_mode);
}

static bool find_pydir(char *out, size_t len)
{
    const char *env = getenv("SHADESWEEP_PYDIR");
    if (env && *env) {
        snprintf(out, len, "%s", env);
        return has_package(out);
    }
    char exe[2048];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = 0;
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = 0;   /* BINDIR */
            snprintf(out, len, "%s/../%s", exe, SHADESWEEP_PYDIR_REL);
            if (has_package(out))
                return true;
        }
    }
    snprintf(out, len, "%s", SHADESWEEP_PYDIR_INSTALLED);
    if (has_package(out))
        return true;
    snprintf(out, len, "%s", SHADESWEEP_PYDIR_SOURCE);
    return has_package(out);
}

int cmd_report(int argc, char **argv)
{
    char dir[4096];
    if (!find_pydir(dir, sizeof dir)) {
        fprintf(stderr, "shadesweep report: the report package (shadesweep_report) is not "
                "installed: looked in %s and %s\n", SHADESWEEP_PYDIR_INSTALLED,
                SHADESWEEP_PYDIR_SOURCE);
        return 2;
    }
    const char *old = getenv("PYTHONPATH");
    char *pp = malloc(strlen(dir) + (old ? strlen(old) : 0) + 2);
    if (!pp) {
        fprintf(stderr, "shadesweep report: out of memory\n");
        return 2;
    }
    sprintf(pp, "%s%s%s", dir, old && *old ? ":" : "", old && *old ? old : "");
    setenv("PYTHONPATH", pp, 1);
    free(pp);
    /* the report asks this program for its statistics (shadesweep ratios) */
    char self[4096];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n > 0) {
        self[n] = '\0';
        setenv("SHADESWEEP_EXE", self, 1);
    }
    char **args = calloc((size_t)argc + 3, sizeof *args);
    if (!args) {
        fprintf(stderr, "shadesweep report: out of memory\n");
        return 2;
    }
    args[0] = "python3";
    args[1] = "-m";
    args[2] = "shadesweep_report";
    for (int i = 1; i < argc; i++)
        args[i + 2] = argv[i];
    /* Debian's python3 (with python3-matplotlib and python3-yaml) before whatever
     * python3 is first on PATH; SHADESWEEP_PYTHON overrides both. */
    const char *py = getenv("SHADESWEEP_PYTHON");
    if (!py || !*py)
        py = access("/usr/bin/python3", X_OK) == 0 ? "/usr/bin/python3" : "python3";
    execvp(py, args);
    fprintf(stderr, "shadesweep report: cannot run %s: %s\n", py, strerror(errno));
    free(args);
    return 2;
}
