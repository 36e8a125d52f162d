#pragma once
/* Moved to common/ (below scenes/ and results/); this include stays for results/
 * users. New code includes common/fsutil.h. */
#include "common/fsutil.h"
