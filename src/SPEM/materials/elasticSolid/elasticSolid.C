#include "elasticSolid.H"

namespace
{

Foam::scalar readPoisson(const Foam::dictionary& dict, const Foam::word& name)
{
    const Foam::scalar nu = dict.get<Foam::scalar>("nu");
    if (!(nu > -1 && nu < 0.5))
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'nu' of region " << name
            << " must lie in (-1, 0.5), found " << nu
            << Foam::exit(Foam::FatalIOError);
    }
    return nu;
}

} // End anonymous namespace


Foam::elasticSolid::elasticSolid(const word& name, const dictionary& dict)
:
    spemMaterial(name, dict),
    E_(readPositive("E")),
    nu_(readPoisson(dict, name)),
    lambda_(E_*nu_/((1 + nu_)*(1 - 2*nu_))),
    mu_(E_/(2*(1 + nu_)))
{}


Foam::scalar Foam::elasticSolid::waveSpeed() const
{
    return std::sqrt((lambda_ + 2*mu_)/rho_);
}
