#pragma once
/* `shadesweep columns`: see columns.c. */
#include <stdbool.h>
#include <stdio.h>

void columns_print(FILE *out, bool markdown);
