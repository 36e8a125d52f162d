// A depth pre-pass (forward-plus): depth only, the colour mask is off.
void main()
{
}
