#include "vgd/low/low.hpp"
