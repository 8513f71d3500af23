#include <biref/biref.h>

int main(void) { return biref_status_string(BIREF_OK) ? 0 : 1; }
