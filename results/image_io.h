#pragma once
/* Moved to common/ (below scenes/ and results/); this include stays for results/
 * users. New code includes common/image_io.h. */
#include "common/image_io.h"
