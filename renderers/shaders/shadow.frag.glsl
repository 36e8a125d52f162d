// The shadows pass writes depth only (the framebuffer has no colour attachment): the
// fixed function stores the fragment's depth, with the pass's polygon offset.
void main()
{
}
