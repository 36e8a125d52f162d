#include "runner/cli.h"
#include "runner/folder.h"

int main(int argc, char **argv)
{
    folder_std_fds();   /* a closed stderr must not become the first file opened */
    return cli_main(argc, argv);
}
