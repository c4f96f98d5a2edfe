#include "rigidBodies.H"
#include "checkKeywords.H"
#include "IOdictionary.H"
#include "Time.H"

const Foam::word Foam::rigidBodies::dictName("rigidBodyProperties");


Foam::rigidBodies::rigidBodies(const Time& runTime)
:
    rigidBodies
    (
        static_cast<const dictionary&>
        (
            IOdictionary
            (
                IOobject
                (
                    dictName,
                    runTime.constant(),
                    runTime,
                    IOobject::READ_IF_PRESENT,
                    IOobject::NO_WRITE,
                    false
                )
            )
        )
    )
{}


Foam::rigidBodies::rigidBodies(const dictionary& dict)
:
    elementContactDistance_
    (
        dict.getOrDefault<scalar>("elementContactDistance", 0.25)
    )
{
    checkKeywords(dict, {"bodies", "elementContactDistance"});
    if (!(elementContactDistance_ > 0 && elementContactDistance_ <= 0.5))
    {
        FatalIOErrorInFunction(dict)
            << "elementContactDistance " << elementContactDistance_
            << " must lie in (0, 0.5] mean fluid element spacings"
            << " (default 0.25)" << exit(FatalIOError);
    }

    const entry* bodiesEntry = dict.findEntry("bodies", keyType::LITERAL);
    if (!bodiesEntry)
    {
        return;
    }
    if (!bodiesEntry->isDict())
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'bodies' of " << dict.name()
            << " must be a dictionary of bodies, each a sub-dictionary:"
            << nl << "    bodies { wedge { shape polygon; ... } }"
            << exit(FatalIOError);
    }

    const dictionary& bodiesDict = bodiesEntry->dict();
    for (const entry& e : bodiesDict)
    {
        if (!e.isDict())
        {
            FatalIOErrorInFunction(bodiesDict)
                << "Entry '" << e.keyword() << "' of " << bodiesDict.name()
                << " must be a sub-dictionary: "
                << e.keyword() << " { shape polygon; ... }"
                << exit(FatalIOError);
        }
        append(new rigidBody(e.keyword(), e.dict()));
    }
}


Foam::label Foam::rigidBodies::findBody(const word& name) const
{
    forAll(*this, i)
    {
        if (operator[](i).name() == name)
        {
            return i;
        }
    }
    return -1;
}


Foam::bodySurfaces Foam::rigidBodies::surfaces() const
{
    bodySurfaces s;
    s.reserve(size());
    for (const rigidBody& body : *this)
    {
        const rigidBody* b = &body;
        s.push_back
        (
            {
                body.name(),
                [b](const scalar x, const scalar y)
                {
                    return b->signedDistance(x, y);
                }
            }
        );
    }
    return s;
}


bool Foam::rigidBodies::anySliding() const
{
    forAll(*this, i)
    {
        if
        (
            operator[](i).elementsContact()
         == rigidBody::elementContact::slide
        )
        {
            return true;
        }
    }
    return false;
}


void Foam::rigidBodies::writeState(dictionary& dict) const
{
    for (const rigidBody& body : *this)
    {
        dictionary bodyDict;
        body.writeState(bodyDict);
        dict.set(body.name(), bodyDict);
    }
}


void Foam::rigidBodies::readState(const dictionary& dict)
{
    for (rigidBody& body : *this)
    {
        const dictionary* bodyDict = dict.findDict(body.name());
        if (!bodyDict)
        {
            FatalIOErrorInFunction(dict)
                << "No state of rigid body '" << body.name() << "' in "
                << dict.name() << exit(FatalIOError);
        }
        body.readState(*bodyDict);
    }
}
