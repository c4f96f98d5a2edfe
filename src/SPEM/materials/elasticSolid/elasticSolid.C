#include "elasticSolid.H"
#include "OStringStream.H"

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


//- The `hypothesis` entry, planeStrain if absent. Read by hand rather
//  than with Enum::getOrDefault, whose errors name neither the keyword
//  (unknown word) nor the entry (a number or a list)
Foam::elasticSolid::hypothesis readHypothesis
(
    const Foam::dictionary& dict,
    const Foam::word& name
)
{
    using namespace Foam;
    const entry* eptr = dict.findEntry("hypothesis", keyType::LITERAL);
    if (!eptr) return elasticSolid::hypothesis::planeStrain;

    OStringStream found;
    if (eptr->isStream())
    {
        const ITstream& is = eptr->stream();
        if
        (
            is.size() == 1 && is[0].isWord()
         && elasticSolid::hypothesisNames.found(is[0].wordToken())
        )
        {
            return elasticSolid::hypothesisNames.get(is[0].wordToken());
        }
        forAll(is, i) found << (i ? " " : "") << is[i];
    }
    else
    {
        found << "a sub-dictionary";
    }
    FatalIOErrorInFunction(dict)
        << "Entry 'hypothesis' of region " << name << " must be one of "
        << elasticSolid::hypothesisNames.names() << ", found '"
        << found.str().c_str() << "'" << exit(FatalIOError);
    return elasticSolid::hypothesis::planeStrain;
}

} // End anonymous namespace


Foam::elasticSolid::elasticSolid(const word& name, const dictionary& dict)
:
    spemMaterial(name, dict),
    E_(readChecked("E", saneRange::youngsModulus)),
    nu_(readPoisson(dict, name)),
    hypothesis_(readHypothesis(dict, name)),
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
