#include "checkKeywords.H"
#include "OStringStream.H"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <vector>

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


namespace
{

//- Letters to change, insert, delete or swap to turn a into b, ignoring
//  case (optimal string alignment distance)
std::size_t editDistance(const std::string& a, const std::string& b)
{
    const auto lower = [](const char c) { return char(std::tolower(c)); };
    const std::size_t n = a.size(), m = b.size();
    std::vector<std::vector<std::size_t>> d
    (
        n + 1, std::vector<std::size_t>(m + 1, 0)
    );
    for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= n; ++i)
    {
        for (std::size_t j = 1; j <= m; ++j)
        {
            const std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
            d[i][j] =
                std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if
            (
                i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2])
             && lower(a[i - 2]) == lower(b[j - 1])
            )
            {
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
            }
        }
    }
    return d[n][m];
}

} // End anonymous namespace


void Foam::checkKeywordSpelling(const dictionary& dict, const wordList& known)
{
    for (const entry& e : dict)
    {
        const word& key = e.keyword();
        if (known.found(key)) continue;
        for (const word& k : known)
        {
            // One letter off for short names, two for longer ones
            const std::size_t allowed = k.size() <= 5 ? 1 : 2;
            if (editDistance(key, k) <= allowed)
            {
                FatalIOErrorInFunction(dict)
                    << "Unknown keyword '" << key << "' in " << dict.name()
                    << ": did you mean '" << k << "'?" << nl
                    << "Known keywords: " << known << exit(FatalIOError);
            }
        }
    }
}


void Foam::outOfRange
(
    const dictionary& dict,
    const word& key,
    const scalar value,
    const valueRange& range,
    const std::string& what
)
{
    FatalIOErrorInFunction(dict)
        << "Entry '" << key << "' in " << dict.name() << ": "
        << (what.empty() ? std::string("the value") : what).c_str() << ' '
        << value << (std::isfinite(value) ? " is out of range" : " is not finite")
        << nl << "    Allowed: " << (range.lowerOpen ? "(" : "[")
        << range.lower << ", " << range.upper << "] " << range.unit << ": "
        << range.why << exit(FatalIOError);
    std::abort();
}


Foam::scalar Foam::getChecked
(
    const dictionary& dict,
    const word& key,
    const valueRange& range
)
{
    const scalar value = dict.get<scalar>(key);
    if (!range.holds(value)) outOfRange(dict, key, value, range);
    return value;
}


Foam::scalar Foam::getCheckedOrDefault
(
    const dictionary& dict,
    const word& key,
    const scalar deflt,
    const valueRange& range
)
{
    if (!dict.found(key)) return deflt;
    return getChecked(dict, key, range);
}


Foam::vector Foam::getCheckedVector
(
    const dictionary& dict,
    const word& key,
    const valueRange& magnitude,
    const vector* deflt
)
{
    if (deflt && !dict.found(key)) return *deflt;
    const vector v = dict.get<vector>(key);
    for (direction c = 0; c < vector::nComponents; ++c)
    {
        if (!std::isfinite(v[c]))
        {
            outOfRange(dict, key, v[c], magnitude, "a component");
        }
    }
    // |v| without overflow: a component of 1e200 squares to infinity
    const scalar scale = cmptMax(cmptMag(v));
    const scalar m = scale > 0 ? scale*mag(v/scale) : 0;
    if (!magnitude.holds(m)) outOfRange(dict, key, m, magnitude, "the magnitude");
    return v;
}


Foam::label Foam::checkedWordIndex
(
    const dictionary& dict,
    const word& key,
    const wordList& allowed,
    const bool required,
    const std::string& what
)
{
    const std::string entryName =
        "Entry '" + key + "'" + (what.empty() ? "" : " " + what);
    const entry* eptr = dict.findEntry(key, keyType::LITERAL);
    if (!eptr)
    {
        if (!required) return -1;
        FatalIOErrorInFunction(dict)
            << entryName.c_str() << " is missing: give one of " << allowed
            << exit(FatalIOError);
    }
    OStringStream found;
    if (eptr->isStream())
    {
        const ITstream& is = eptr->stream();
        if (is.size() == 1 && is[0].isWord())
        {
            const label i = allowed.find(is[0].wordToken());
            if (i >= 0) return i;
        }
        forAll(is, i) found << (i ? " " : "") << is[i];
    }
    else
    {
        found << "a sub-dictionary";
    }
    FatalIOErrorInFunction(dict)
        << entryName.c_str() << " must be one of " << allowed << ", found '"
        << found.str().c_str() << "'" << exit(FatalIOError);
    return -1;
}
