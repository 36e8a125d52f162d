#pragma once
/* Moved to common/ (below scenes/ and results/); this include stays for results/
 * users. New code includes common/grow.h. */
#include "common/grow.h"
