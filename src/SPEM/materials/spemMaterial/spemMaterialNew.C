#include "spemMaterial.H"
#include "checkKeywords.H"

Foam::autoPtr<Foam::spemMaterial> Foam::spemMaterial::New
(
    const word& name,
    const dictionary& dict
)
{
    const word modelType(dict.get<word>("model"));

    if (!dictionaryConstructorTablePtr_)
    {
        FatalErrorInFunction
            << "The material selection table is empty: libSPEM was not"
            << " loaded (linked with --as-needed?)" << exit(FatalError);
    }

    auto cstrIter = dictionaryConstructorTablePtr_->cfind(modelType);

    if (!cstrIter.found())
    {
        FatalIOErrorInLookup
        (
            dict,
            "model",
            modelType,
            *dictionaryConstructorTablePtr_
        ) << exit(FatalIOError);
    }

    autoPtr<spemMaterial> model(cstrIter()(name, dict));
    checkKeywords(dict, model->keywords());
    return model;
}
