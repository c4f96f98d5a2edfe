#include "patchConditions.H"

#include <cmath>

void Foam::nodeConstraints
(
    const triMesh& mesh,
    const List<patchType>& patchTypes,
    const scalar cornerAngleDeg,
    std::vector<elementModel::constraint>& c,
    std::vector<scalar>& normal,
    const std::vector<scalar>* triangleViscosity,
    std::vector<scalar>* wallFriction,
    const List<bool>* slidingPatch
)
{
    using constraint = elementModel::constraint;
    const label nNodes = mesh.nPoints();
    const std::vector<scalar>& X = mesh.points();
    c.assign(nNodes, constraint::free);
    normal.assign(2*nNodes, 0);
    std::vector<scalar> minCos(nNodes, 1);

    // Weak no-slip: nodes that no solid element shares
    std::vector<bool> fluidNode;
    if (triangleViscosity && wallFriction)
    {
        wallFriction->assign(nNodes, 0);
        fluidNode.assign(nNodes, true);
        const std::vector<label>& tri = mesh.triangles();
        for (label t = 0; t < mesh.nTriangles(); ++t)
        {
            if ((*triangleViscosity)[t] < 0)
            {
                for (label k = 0; k < 3; ++k) fluidNode[tri[3*t + k]] = false;
            }
        }
    }

    for (label s = 0; s < mesh.nSegments(); ++s)
    {
        const patchType t = patchTypes[mesh.segmentPatch()[s]];
        const label a = mesh.segments()[2*s], b = mesh.segments()[2*s + 1];
        if
        (
            t != patchType::clamped && t != patchType::noSlipWall
         && t != patchType::slipWall
        )
        {
            continue;
        }
        // A node that slides on this side: on a slip wall, and with the
        // wall shear on a no-slip wall if only fluid elements share it
        const bool sliding =
            !slidingPatch || (*slidingPatch)[mesh.segmentPatch()[s]];
        const auto slides = [&](const label v)
        {
            return
                t == patchType::slipWall
             || (
                    t == patchType::noSlipWall && sliding
                 && !fluidNode.empty() && fluidNode[v]
                );
        };
        scalar friction = 0;
        if (t == patchType::noSlipWall && (slides(a) || slides(b)))
        {
            // mu l_s/h_s to each node, h_s = 2 A_e/l_s
            const label k = mesh.segmentEdge()[s];
            const label e =
                max(mesh.edgeTriangles()[2*k], mesh.edgeTriangles()[2*k + 1]);
            const scalar area = std::abs(mesh.triangleArea(e));
            const scalar l2 =
                sqr(X[2*b] - X[2*a]) + sqr(X[2*b + 1] - X[2*a + 1]);
            friction = max((*triangleViscosity)[e], scalar(0))*l2/(2*area);
        }
        // Outward normal: the element lies left of a -> b
        const scalar dx = X[2*b] - X[2*a], dy = X[2*b + 1] - X[2*a + 1];
        const scalar len = std::sqrt(dx*dx + dy*dy);
        const scalar n[2] = {dy/len, -dx/len};
        for (const label v : {a, b})
        {
            if (!slides(v))
            {
                c[v] = constraint::fixed;
                continue;
            }
            if (friction > 0) (*wallFriction)[v] += friction;
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

    const scalar cornerCos = std::cos(cornerAngleDeg*M_PI/180);
    for (label v = 0; v < nNodes; ++v)
    {
        const scalar len = std::hypot(normal[2*v], normal[2*v + 1]);
        if (c[v] == constraint::fixed || len == 0)
        {
            normal[2*v] = normal[2*v + 1] = 0;
            if (!fluidNode.empty()) (*wallFriction)[v] = 0;
            continue;
        }
        if (minCos[v] < cornerCos)
        {
            c[v] = constraint::fixed;
            if (!fluidNode.empty()) (*wallFriction)[v] = 0;
        }
        else
        {
            c[v] = constraint::slip;
            normal[2*v] /= len;
            normal[2*v + 1] /= len;
        }
    }
}
