#include "spemFunctionObject.H"
#include "Time.H"

Foam::functionObjects::spemFunctionObject::spemFunctionObject
(
    const word& name,
    const Time& runTime,
    const dictionary& dict,
    const needs what
)
:
    timeFunctionObject(name, runTime),
    writeFile(runTime, name, name, dict),
    needs_(what)
{
    // writeFile sets a field width for its value columns, which would pad
    // the first header line
    if (writeToFile()) file().width(0);
}


const Foam::spemModel&
Foam::functionObjects::spemFunctionObject::model() const
{
    if (!time_.foundObject<spemModel>("spemProperties"))
    {
        FatalErrorInFunction
            << "Function object " << name() << " of type " << type()
            << " needs the SPEM model: run it from spemFoam"
            << exit(FatalError);
    }
    return time_.lookupObject<spemModel>("spemProperties");
}


const Foam::elementModel&
Foam::functionObjects::spemFunctionObject::elements() const
{
    const spemModel& m = model();
    if (!m.hasElements())
    {
        FatalErrorInFunction
            << "Function object " << name() << " of type " << type()
            << " needs elements, but this case has no elements (method "
            << m.methodName() << ')'
            << exit(FatalError);
    }
    return m.elements();
}


const Foam::sphFluid&
Foam::functionObjects::spemFunctionObject::particles() const
{
    const spemModel& m = model();
    if (!m.hasParticles())
    {
        FatalErrorInFunction
            << "Function object " << name() << " of type " << type()
            << " needs particles, but this case has none (method "
            << m.methodName() << ')'
            << exit(FatalError);
    }
    return m.particles();
}


bool Foam::functionObjects::spemFunctionObject::execute()
{
    if (needs_ == needs::elements) elements();
    // method SPEM: particles appear at the first conversion
    if (needs_ == needs::particles && !model().hasElements()) particles();
    return true;
}


void Foam::functionObjects::spemFunctionObject::writeColumns
(
    const wordList& columns
)
{
    if (!writeToFile()) return;
    OFstream& os = file();
    os  << "# Time";
    for (const word& c : columns) os << tab << c;
    os  << endl;
}


void Foam::functionObjects::spemFunctionObject::readPoint
(
    const dictionary& dict,
    const word& key,
    scalar& x,
    scalar& y
)
{
    const vector p = dict.get<vector>(key);
    x = p.x();
    y = p.y();
}
