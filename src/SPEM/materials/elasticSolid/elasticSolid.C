#include "elasticSolid.H"
#include "checkKeywords.H"

const Foam::Enum<Foam::elasticSolid::hypothesis>
Foam::elasticSolid::hypothesisNames
({
    {hypothesis::planeStrain, "planeStrain"},
    {hypothesis::planeStress, "planeStress"}
});


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
    E_(readChecked("E", saneRange::youngsModulus)),
    nu_(readPoisson(dict, name)),
    hypothesis_
    (
        getCheckedEnum
        (
            dict, "hypothesis", hypothesisNames, hypothesis::planeStrain,
            "of region " + name
        )
    ),
    lambda_(E_*nu_/((1 + nu_)*(1 - 2*nu_))),
    mu_(E_/(2*(1 + nu_))),
    planeLambda_
    (
        hypothesis_ == hypothesis::planeStress
      ? 2*lambda_*mu_/(lambda_ + 2*mu_)
      : lambda_
    )
{}


Foam::scalar Foam::elasticSolid::waveSpeed() const
{
    return std::sqrt((planeLambda_ + 2*mu_)/rho_);
}
