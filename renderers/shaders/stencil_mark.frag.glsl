// Stencil marking of a light volume (seed 000 4.5.8, seed 003 4.2.2): the "null
// shader". Colour writes are masked off and depth writes are off; only the stencil
// operations on depth fail do the work.
void main()
{
}
