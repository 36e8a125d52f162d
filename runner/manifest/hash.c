/* FNV-1a 64 and hex formatting (hash.h). */
#include "runner/manifest/hash.h"

uint64_t fnv1a64_update(uint64_t h, const void *data, size_t len)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < len; i++) {
        h ^= p[i];
        h *= FNV1A64_PRIME;
    }
    return h;
}

uint64_t fnv1a64(const void *data, size_t len)
{
    return fnv1a64_update(FNV1A64_OFFSET_BASIS, data, len);
}

void hash_hex(uint64_t h, unsigned digits, char *out)
{
    static const char hex[] = "0123456789abcdef";
    if (digits > 16)
        digits = 16;
    for (unsigned i = 0; i < digits; i++)
        out[i] = hex[(h >> (60 - 4 * i)) & 0xf];
    out[digits] = '\0';
}
