#include "patchType.H"

const Foam::Enum<Foam::patchType> Foam::patchTypeNames
({
    { patchType::clamped, "clamped" },
    { patchType::slipWall, "slipWall" },
    { patchType::noSlipWall, "noSlipWall" },
    { patchType::freeSurface, "freeSurface" },
});
