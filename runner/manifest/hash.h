#pragma once
/* FNV-1a 64 (http://www.isthe.com/chongo/tech/comp/fnv/) and its hex form.
 * Used for the manifest hash (all 16 hex digits of the file's bytes) and run ids
 * (the first 12 hex digits of the hash of a run's canonical text). Not
 * cryptographic: it names things, it does not protect them. */
#include <stddef.h>
#include <stdint.h>

#define FNV1A64_OFFSET_BASIS UINT64_C(0xcbf29ce484222325)
#define FNV1A64_PRIME UINT64_C(0x100000001b3)

/* The hash of len bytes. */
uint64_t fnv1a64(const void *data, size_t len);
/* Continues a hash: fnv1a64(ab) == fnv1a64_update(fnv1a64(a), b). Start from
 * FNV1A64_OFFSET_BASIS. */
uint64_t fnv1a64_update(uint64_t h, const void *data, size_t len);
/* The first `digits` (1..16) of the 16 lowercase hex digits of h, most significant
 * first, NUL-terminated: out holds digits + 1 bytes. digits > 16 counts as 16. */
void hash_hex(uint64_t h, unsigned digits, char *out);
