#include "checkKeywords.H"

void Foam::checkKeywords(const dictionary& dict, const wordList& allowed)
{
    for (const entry& e : dict)
    {
        if (!allowed.found(e.keyword()))
        {
            FatalIOErrorInFunction(dict)
                << "Unknown keyword '" << e.keyword() << "' in "
                << dict.name() << nl << "Valid keywords: " << allowed
                << exit(FatalIOError);
        }
    }
}
