#include "patchConditions.H"

#include <cmath>

void Foam::nodeConstraints
(
    const triMesh& mesh,
    const List<patchType>& patchTypes,
    const scalar cornerAngleDeg,
    std::vector<elementModel::constraint>& c,
    std::vector<scalar>& normal
)
{
    using constraint = elementModel::constraint;
    const label nNodes = mesh.nPoints();
    const std::vector<scalar>& X = mesh.points();
    c.assign(nNodes, constraint::free);
    normal.assign(2*nNodes, 0);
    std::vector<scalar> minCos(nNodes, 1);

    for (label s = 0; s < mesh.nSegments(); ++s)
    {
        const patchType t = patchTypes[mesh.segmentPatch()[s]];
        const label a = mesh.segments()[2*s], b = mesh.segments()[2*s + 1];
        if (t == patchType::clamped || t == patchType::noSlipWall)
        {
            c[a] = c[b] = constraint::fixed;
        }
        else if (t == patchType::slipWall)
        {
            // Outward normal: the element lies left of a -> b
            const scalar dx = X[2*b] - X[2*a], dy = X[2*b + 1] - X[2*a + 1];
            const scalar len = std::sqrt(dx*dx + dy*dy);
            const scalar n[2] = {dy/len, -dx/len};
            for (const label v : {a, b})
            {
                const scalar sum = std::hypot(normal[2*v], normal[2*v + 1]);
                if (sum > 0)
                {
                    const scalar cosAngle =
                        (normal[2*v]*n[0] + normal[2*v + 1]*n[1])/sum;
                    minCos[v] = std::min(minCos[v], cosAngle);
                }
                normal[2*v] += n[0];
                normal[2*v + 1] += n[1];
            }
        }
    }

    const scalar cornerCos = std::cos(cornerAngleDeg*M_PI/180);
    for (label v = 0; v < nNodes; ++v)
    {
        const scalar len = std::hypot(normal[2*v], normal[2*v + 1]);
        if (c[v] == constraint::fixed || len == 0)
        {
            normal[2*v] = normal[2*v + 1] = 0;
            continue;
        }
        if (minCos[v] < cornerCos)
        {
            c[v] = constraint::fixed;
        }
        else
        {
            c[v] = constraint::slip;
            normal[2*v] /= len;
            normal[2*v + 1] /= len;
        }
    }
}
