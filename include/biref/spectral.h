/* biref — spectral (placeholder, filled by its issue). */
#ifndef BIREF_SPECTRAL_H
#define BIREF_SPECTRAL_H
#include "biref/common.h"
#endif
