#include "costBreakdown.H"

#include <algorithm>
#include <sstream>

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

const char* const Foam::costBreakdown::names_[nParts] =
{
    "elements",
    "particles",
    "search",
    "couplings",
    "conversion",
    "bodies",
    "output",
    "functions"
};


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::costBreakdown::part Foam::costBreakdown::switchTo(const part p)
{
    const clock::time_point now = clock::now();
    if (current_ != nParts)
    {
        seconds_[current_] +=
            std::chrono::duration<double>(now - since_).count();
    }
    const part before = current_;
    current_ = p;
    since_ = now;
    return before;
}


void Foam::costBreakdown::print
(
    Ostream& os,
    const std::array<double, nParts>& s,
    const double wall,
    const bool withSeconds
) const
{
    // Shares to 0.1 %, seconds to 1 ms, whatever the precision of the
    // log's stream (writePrecision)
    std::ostringstream line;
    line.setf(std::ios::fixed);
    const auto share = [&line, wall](const double t)
    {
        line.precision(1);
        line << (wall > 0 ? 100*t/wall : 0.0) << " %";
    };
    const auto seconds = [&line](const double t)
    {
        line.precision(3);
        line << ' ' << t << " s";
    };

    double timed = 0;
    for (const double t : s) timed += t;
    // Two clock reads apart, the loop's wall can fall a hair short of the
    // parts inside it
    const double other = std::max(wall - timed, 0.0);

    for (label p = 0; p < nParts; ++p)
    {
        // The particle half with its search, which is shown inside it
        const double t = p == particles ? s[p] + s[search] : s[p];
        line<< (p == 0 ? "" : p == search ? " (" : ", ") << names_[p] << ' ';
        share(t);
        if (withSeconds && t > 0) seconds(t);
        if (p == search) line << ')';
    }
    line<< ", other ";
    share(other);
    if (withSeconds && other > 0) seconds(other);
    os  << line.str().c_str() << nl;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::costBreakdown::costBreakdown()
:
    start_(clock::now()),
    lastReport_(start_),
    current_(nParts),
    since_(start_)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::costBreakdown::startLoop()
{
    seconds_.fill(0);
    secondsAtReport_.fill(0);
    start_ = clock::now();
    lastReport_ = start_;
    since_ = start_;
}


double Foam::costBreakdown::wall() const
{
    return std::chrono::duration<double>(clock::now() - start_).count();
}


void Foam::costBreakdown::reportInterval(Ostream& os)
{
    const clock::time_point now = clock::now();
    const double wall =
        std::chrono::duration<double>(now - lastReport_).count();
    std::array<double, nParts> s;
    for (label p = 0; p < nParts; ++p)
    {
        s[p] = seconds_[p] - secondsAtReport_[p];
    }
    std::ostringstream head;
    head.setf(std::ios::fixed);
    head.precision(3);
    head<< "Cost since the last log (" << wall << " s wall): ";
    os  << head.str().c_str();
    print(os, s, wall, false);
    secondsAtReport_ = seconds_;
    lastReport_ = now;
}


void Foam::costBreakdown::reportRun(Ostream& os) const
{
    const double w = wall();
    std::ostringstream head;
    head.setf(std::ios::fixed);
    head.precision(3);
    head<< "Cost of the run (" << w << " s wall): ";
    os  << head.str().c_str();
    print(os, seconds_, w, true);
}


// ************************************************************************* //
