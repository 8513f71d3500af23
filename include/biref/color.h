/* biref — color (placeholder, filled by its issue). */
#ifndef BIREF_COLOR_H
#define BIREF_COLOR_H
#include "biref/common.h"
#endif
